#pragma once
// The optimal motion spaces of paper section 3.1 (eq. 4-6). The pursuer keeps its heading within
// alpha2* = asin(vE / vP) of the line P->E; the evader keeps alpha1 >= pi/2 from the line E->P, i.e.
// within pi/2 of the direction P->E pointing away from the pursuer. Both are cones about an axis.

#include "geometry/vector.hpp"

namespace peg3d {

/// A solid cone of directions: every direction within `half_angle` of `axis`.
struct Cone {
  Vec3 axis = Vec3::UnitX();  ///< unit axis
  double half_angle = 0.0;    ///< rad, in [0, pi]

  /// True when the non-zero direction d lies inside the cone (to `tolerance` rad).
  bool contains(const Vec3& d, double tolerance = 1e-12) const;
  /// The unit direction of the cone closest in angle to d: d itself (normalized) when inside, else d
  /// rotated towards the axis in the plane of d and axis onto the cone's surface. A d opposite to the
  /// axis picks a fixed perpendicular plane so the result is deterministic.
  Vec3 project(const Vec3& d) const;
};

/// alpha2* = asin(vE / vP) (eq. 6), rad. For vE >= vP the cone opens to a half-space (pi/2).
/// Throws InvalidParameter on a non-positive pursuer speed, a negative evader speed or non-finite ones.
double pursuer_cone_half_angle(double pursuer_speed, double evader_speed);

/// The pursuer's motion cone about P->E. P and E must differ.
Cone pursuer_motion_cone(const Vec3& pursuer, const Vec3& evader, double pursuer_speed, double evader_speed);

/// The evader's motion space alpha1 >= pi/2 as a cone of half-angle pi/2 about P->E. P and E must differ.
Cone evader_motion_cone(const Vec3& pursuer, const Vec3& evader);

/// Some unit vector perpendicular to the non-zero v, chosen deterministically.
Vec3 any_perpendicular(const Vec3& v);

}  // namespace peg3d
