#include "geometry/motion_cone.hpp"

#include <cassert>
#include <cmath>

#include "core/validation.hpp"
#include "geometry/angles.hpp"

namespace peg3d {

bool Cone::contains(const Vec3& d, double tolerance) const { return angle_between(d, axis) <= half_angle + tolerance; }

ConeMembership::ConeMembership(const Cone& cone, double tolerance)
    : cone_(cone), tolerance_(tolerance), cos_limit_(std::cos(cone.half_angle + tolerance)) {}

bool ConeMembership::operator()(const Vec3& d) const {
  // cos(angle) from the dot product is off by a few ulps, far less than the margin, and the angle moves at
  // least as much as its cosine: outside the margin the answer is contains()'s. Inside it, contains() decides.
  constexpr double kMargin = 1e-9;
  const double norms = d.norm() * cone_.axis.norm();
  if (norms > 0.0) {
    const double c = d.dot(cone_.axis) / norms;
    if (c > cos_limit_ + kMargin) return true;
    if (c < cos_limit_ - kMargin) return false;
  }
  return cone_.contains(d, tolerance_);
}

Vec3 Cone::project(const Vec3& d) const { return project(d, Vec3::Zero(), 0.0); }

Vec3 Cone::project(const Vec3& d, const Vec3& hint, double commit_angle) const {
  const Vec3 u = d.normalized();
  if (angle_between(u, axis) <= half_angle) return u;
  const auto perpendicular = [&](const Vec3& v) { return Vec3(v - v.dot(axis) * axis); };
  Vec3 w = perpendicular(u);
  if (commit_angle > 0.0 && angle_between(u, -axis) < commit_angle && perpendicular(hint).norm() > 1e-6) {
    w = perpendicular(hint);
  }
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

Vec3 project_within_band(const Cone& cone, const Vec3& d, double polar_margin, const Vec3& hint,
                         double commit_angle) {
  const Vec3 c = cone.project(d, hint, commit_angle);
  const Heading hc = heading_of(c);
  if (hc.theta >= polar_margin && hc.theta <= kPi - polar_margin) return c;
  // Search the band's edge circle between c's azimuth and the axis's azimuth (the edge point nearest to
  // the axis) for the first direction inside the cone.
  const double edge = hc.theta < polar_margin ? polar_margin : kPi - polar_margin;
  const Heading ha = heading_of(cone.axis);
  const bool axis_vertical = cone.axis.x() == 0.0 && cone.axis.y() == 0.0;
  const double a0 = hc.alpha, a1 = axis_vertical ? hc.alpha : a0 + wrap_angle(ha.alpha - a0);
  const auto on_edge = [&](double alpha) { return direction(Heading{alpha, edge}); };
  const ConeMembership inside(cone);
  if (inside(on_edge(a0))) return on_edge(a0);
  if (!inside(on_edge(a1))) return on_edge(a1);  // no direction satisfies both: stay near the axis
  double lo = 0.0, hi = 1.0;  // on_edge(a0 + lo (a1 - a0)) is outside, at hi inside
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (inside(on_edge(a0 + mid * (a1 - a0))) ? hi : lo) = mid;
  }
  return on_edge(a0 + hi * (a1 - a0));
}

Vec3 first_inside_on_arc(const Cone& cone, const Vec3& from, const Vec3& to) {
  if (cone.contains(from)) return from;
  const double omega = angle_between(from, to);
  if (omega < 1e-12) return to;
  // Spherical interpolation; sin(omega) ~ 0 only for opposite directions, where any great circle will do.
  const Vec3 side = omega > kPi - 1e-9 ? any_perpendicular(from) : Vec3((to - std::cos(omega) * from).normalized());
  const auto at = [&](double t) { return Vec3(std::cos(t * omega) * from + std::sin(t * omega) * side); };
  const ConeMembership inside(cone);
  double lo = 0.0, hi = 1.0;  // at(lo) outside, at(hi) inside
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (inside(at(mid)) ? hi : lo) = mid;
  }
  return at(hi).normalized();
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
