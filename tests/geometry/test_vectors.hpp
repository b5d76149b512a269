#pragma once
// Random vectors for geometry tests, from a fixed seed.

#include <random>

#include "core/random.hpp"
#include "geometry/vector.hpp"

namespace peg3d::testing {

inline Vec3 random_point(Rng& rng, double extent = 30.0) {
  std::uniform_real_distribution<double> u(-extent, extent);
  return {u(rng), u(rng), u(rng)};
}

inline Vec3 random_unit(Rng& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vec3 v;
  do v = Vec3(n(rng), n(rng), n(rng));
  while (v.norm() < 1e-6);
  return v.normalized();
}

}  // namespace peg3d::testing
