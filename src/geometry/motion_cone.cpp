#include "geometry/motion_cone.hpp"

#include <cassert>
#include <cmath>

#include "core/validation.hpp"
#include "geometry/angles.hpp"

namespace peg3d {

bool Cone::contains(const Vec3& d, double tolerance) const { return angle_between(d, axis) <= half_angle + tolerance; }

Vec3 Cone::project(const Vec3& d) const {
  const Vec3 u = d.normalized();
  if (angle_between(u, axis) <= half_angle) return u;
  Vec3 w = u - u.dot(axis) * axis;  // component perpendicular to the axis
  const double wn = w.norm();
  w = wn > 1e-12 ? Vec3(w / wn) : any_perpendicular(axis);
  return std::cos(half_angle) * axis + std::sin(half_angle) * w;
}

Vec3 any_perpendicular(const Vec3& v) {
  // Cross with the basis vector least aligned with v.
  const Vec3 a = v.cwiseAbs();
  const Vec3 e = (a.x() <= a.y() && a.x() <= a.z()) ? Vec3::UnitX() : (a.y() <= a.z() ? Vec3::UnitY() : Vec3::UnitZ());
  return v.cross(e).normalized();
}

double pursuer_cone_half_angle(double pursuer_speed, double evader_speed) {
  require_positive("pursuer_speed", pursuer_speed);
  require_non_negative("evader_speed", evader_speed);
  const double a = evader_speed / pursuer_speed;
  return a >= 1.0 ? kPi / 2.0 : std::asin(a);
}

Cone pursuer_motion_cone(const Vec3& pursuer, const Vec3& evader, double pursuer_speed, double evader_speed) {
  const Vec3 pe = evader - pursuer;
  assert(pe.norm() > 0.0);
  return {pe.normalized(), pursuer_cone_half_angle(pursuer_speed, evader_speed)};
}

Cone evader_motion_cone(const Vec3& pursuer, const Vec3& evader) {
  const Vec3 pe = evader - pursuer;
  assert(pe.norm() > 0.0);
  return {pe.normalized(), kPi / 2.0};
}

}  // namespace peg3d
