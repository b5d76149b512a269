#pragma once
// The optimal motion spaces of paper section 3.1 (eq. 4-6). The pursuer keeps its heading within
// alpha2* = asin(vE / vP) of the line P->E; the evader keeps alpha1 >= pi/2 from the line E->P, i.e.
// within pi/2 of the direction P->E pointing away from the pursuer. Both are cones about an axis.

#include <array>

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
  /// Like project(d), but when d lies within `commit_angle` (rad) of the direction opposite the axis, the
  /// side to rotate towards is taken from `hint` instead of from d. Near that direction the projection's
  /// side flips with tiny changes of d; a hint such as the current heading makes the choice stick.
  Vec3 project(const Vec3& d, const Vec3& hint, double commit_angle) const;
};

/// cone.contains(d, tolerance), the same answer, for testing many directions against one cone (the
/// bisections below): a cosine compared with a margin decides all but the directions within about 1e-9 rad
/// of the surface, and contains() decides those, instead of an atan2 for every one.
class ConeMembership {
 public:
  explicit ConeMembership(const Cone& cone, double tolerance = 1e-12);
  bool operator()(const Vec3& d) const;
  /// cos(half angle + tolerance): the cosine of the angle to the axis at which membership ends.
  double cos_limit() const { return cos_limit_; }

 private:
  const Cone& cone_;
  double tolerance_;
  double cos_limit_;
};

/// The unit direction nearest to d that lies in the cone and whose polar angle lies in [polar_margin,
/// pi - polar_margin] (a climb/dive limit). When the cone and that band do not meet (a narrow cone about a
/// steep axis), the band's direction nearest to the cone's axis. polar_margin = 0 is plain projection.
/// `hint` and `commit_angle` are passed to Cone::project.
Vec3 project_within_band(const Cone& cone, const Vec3& d, double polar_margin, const Vec3& hint = Vec3::Zero(),
                         double commit_angle = 0.0);

/// Walks the great-circle arc from the unit direction `from` to the unit direction `to` and returns the first
/// direction inside the cone (to within 1e-9 of the arc). `to` must lie inside; if `from` does it is returned.
Vec3 first_inside_on_arc(const Cone& cone, const Vec3& from, const Vec3& to);

/// Up to two unit directions (no allocation: it serves the game's step).
struct Directions {
  std::array<Vec3, 2> at;
  int count = 0;
  const Vec3* begin() const { return at.data(); }
  const Vec3* end() const { return at.data() + count; }
};

/// The unit directions on the surfaces of both cones (where their boundary circles cross): none, one (they
/// touch) or two. Cones with (anti)parallel axes have none or a whole circle in common; both give none.
Directions boundary_crossings(const Cone& a, const Cone& b);

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
