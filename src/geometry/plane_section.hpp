#pragma once
// The polygon in which a plane cuts a convex region (a box and half-spaces), and a polygon's area centroid: the
// face two agents share in a Voronoi partition of a box (players/scripted_policies.hpp's VoronoiPursuer).

#include <span>
#include <vector>

#include "geometry/half_spaces.hpp"
#include "geometry/vector.hpp"

namespace peg3d {

/// Writes into `corners` the convex polygon, corners in order, in which the plane through `point` with the unit
/// `normal` cuts the box and every half-space of `cuts` (their offsets of any sign); empty when it misses them.
/// `scratch` is working storage: with both vectors kept by the caller, a call allocates nothing after the first.
void plane_section(const Vec3& point, const Vec3& normal, const Box& box, std::span<const HalfSpace> cuts,
                   std::vector<Vec3>& corners, std::vector<Vec3>& scratch);

/// The area centroid of a planar convex polygon (corners in order) with the unit `normal` of its plane; for
/// a polygon of no area (fewer than three corners, or all on a line) the mean of its corners. It must not be empty.
Vec3 polygon_centroid(std::span<const Vec3> corners, const Vec3& normal);

}  // namespace peg3d
