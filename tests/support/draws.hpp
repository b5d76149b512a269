#pragma once

// A uniform draw in [lo, hi) through the standard distribution, for tests that place random layouts (their cases
// are this distribution's, not core/random.hpp's uniform).
#include <random>

#include "core/random.hpp"

namespace peg3d::testing {

inline double uniform_draw(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

}  // namespace peg3d::testing
