#pragma once
// The nearest point of an intersection of half-spaces: how the obstacle guard slides an agent's step along
// every surface it would otherwise come too near.

#include <span>

#include "geometry/vector.hpp"

namespace peg3d {

/// The half-space {v : v . normal <= offset}.
struct HalfSpace {
  Vec3 normal = Vec3::UnitX();  ///< unit
  double offset = 0.0;          ///< >= 0: the origin lies inside
};

/// The point nearest to m that lies in every half-space (within 1e-12 on each): m itself when it does. The
/// nearest point of a convex polytope lies on one of its facets, edges or vertices, so it is the nearest of m's
/// projections onto each bounding plane, onto each line where two of them cross, and of the points where
/// three of them meet, that lie inside them all; the origin is inside by the precondition, so one always
/// does. Meant for a dozen half-spaces (the vertices are all triples).
Vec3 nearest_within(const Vec3& m, std::span<const HalfSpace> half_spaces);

}  // namespace peg3d
