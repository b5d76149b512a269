#pragma once
// When do two spheres moving in straight lines over one step first touch?

#include <optional>

#include "geometry/vector.hpp"

namespace peg3d {

/// Two centres move linearly over a step, a from a0 to a1 and b from b0 to b1, both starting and ending
/// together. Returns the first fraction t in [0, 1] of the step at which their distance is <= `reach` (the
/// sum of the radii, >= 0): 0 when they already touch at the start, nullopt when they stay apart over the
/// whole step.
std::optional<double> first_contact(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double reach);

}  // namespace peg3d
