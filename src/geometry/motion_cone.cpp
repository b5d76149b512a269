#include "geometry/motion_cone.hpp"

#include <cassert>
#include <cmath>
#include <optional>

#include "core/validation.hpp"
#include "geometry/angles.hpp"

namespace peg3d {

namespace {

// Whether d lies within `limit` rad of `axis`, decided by cos(angle) = d . axis / (|d| |axis|) against
// `cos_limit` (cos(limit) to within 1e-11): nullopt within about 1e-9 rad of the surface, far beyond the
// rounding of either side (and the angle moves at least as much as its cosine), where only the exact angle
// may decide.
std::optional<bool> inside_by_cosine(const Vec3& d, const Vec3& axis, double limit, double cos_limit) {
  const double n2 = d.squaredNorm() * axis.squaredNorm();
  if (!(n2 > 0.0 && std::isfinite(n2) && limit > 0.0 && limit < kPi)) return std::nullopt;
  const double c = d.dot(axis) / std::sqrt(n2);
  if (c > cos_limit + 1e-9) return true;
  if (c < cos_limit - 1e-9) return false;
  return std::nullopt;
}

}  // namespace

bool Cone::contains(const Vec3& d, double tolerance) const {
  // The answer is always angle_between(d, axis) <= half_angle + tolerance; the cosine spares its atan2 but
  // at the surface.
  const double limit = half_angle + tolerance;
  if (const auto inside = inside_by_cosine(d, axis, limit, rough_cos(limit))) return *inside;
  return angle_between(d, axis) <= limit;
}

ConeMembership::ConeMembership(const Cone& cone, double tolerance)
    : cone_(cone), tolerance_(tolerance), cos_limit_(std::cos(cone.half_angle + tolerance)) {}

bool ConeMembership::operator()(const Vec3& d) const {
  // Cone::contains with the limit's cosine taken once for all the directions tested.
  const double limit = cone_.half_angle + tolerance_;
  if (const auto inside = inside_by_cosine(d, cone_.axis, limit, cos_limit_)) return *inside;
  return angle_between(d, cone_.axis) <= limit;
}

Vec3 Cone::project(const Vec3& d) const { return project(d, Vec3::Zero(), 0.0); }

Vec3 Cone::project(const Vec3& d, const Vec3& hint, double commit_angle) const {
  const Vec3 u = d.normalized();
  if (contains(u, 0.0)) return u;
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

namespace {

// The first t in (0, 1) where a cos(theta0 + t span) + b sin(theta0 + t span) = q, in closed form; nullopt
// when the curve never reaches q there.
std::optional<double> first_crossing(double a, double b, double q, double theta0, double span) {
  const double r = std::hypot(a, b);
  if (!(r > 0.0) || span == 0.0 || !(std::abs(q) <= r)) return std::nullopt;
  const double phi = std::atan2(b, a), w = std::acos(q / r);
  double first = 1.0;
  for (const double root : {phi + w, phi - w}) {
    for (int k = -3; k <= 3; ++k) {
      const double t = (root + 2.0 * kPi * k - theta0) / span;
      if (t > 0.0 && t < first) first = t;
    }
  }
  if (first >= 1.0) return std::nullopt;
  return first;
}

// The search of the cone's bisections: 40 halvings of [0, 1] keeping inside(point(lo)) false (point(0) is
// outside) and inside(point(hi)) true, returning hi. The curves searched are arcs of at most half a turn, on
// which the angle to the axis has at most one minimum, so they cross the cone's surface at most twice; when
// point(1) is inside too, exactly once, and hi is the first point of the 2^-40 grid inside, whatever the path
// to it. A closed-form guess of that crossing, checked at the two points of the 2^-30 grid around it, then
// stands for the first 30 halvings: the same hi, for a third of the work. Otherwise (point(1) outside, or a
// guess off near a tangency) all 40 halvings run.
template <class Point>
double search_crossing(const ConeMembership& inside, const Point& point, std::optional<double> guess) {
  double lo = 0.0, hi = 1.0;
  int halvings = 40;
  if (guess && inside(point(1.0))) {
    // The guess is usually right to the last grid step: the two points of the 2^-40 grid around it settle
    // the whole search (the same hi as the halvings, which end on that grid).
    constexpr double kFine = 0x1p40;
    const double fl = std::floor(*guess * kFine) / kFine, fh = fl + 1.0 / kFine;
    if (fl >= 0.0 && fh <= 1.0 && !inside(point(fl)) && inside(point(fh))) return fh;
    constexpr double kCoarse = 0x1p30;
    const double l = std::floor(*guess * kCoarse) / kCoarse, h = l + 1.0 / kCoarse;
    if (l >= 0.0 && h <= 1.0 && !inside(point(l)) && inside(point(h))) lo = l, hi = h, halvings = 10;
  }
  for (int i = 0; i < halvings; ++i) {
    const double mid = 0.5 * (lo + hi);
    (inside(point(mid)) ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

Vec3 project_within_band(const Cone& cone, const Vec3& d, double polar_margin, const Vec3& hint,
                         double commit_angle) {
  const Vec3 c = cone.project(d, hint, commit_angle);
  if (within_climb_limit(c, polar_margin)) return c;
  const Heading hc = heading_of(c);
  // Search the band's edge circle between c's azimuth and the axis's azimuth (the edge point nearest to
  // the axis) for the first direction inside the cone.
  const double edge = hc.theta < polar_margin ? polar_margin : kPi - polar_margin;
  const Heading ha = heading_of(cone.axis);
  const bool axis_vertical = cone.axis.x() == 0.0 && cone.axis.y() == 0.0;
  const double a0 = hc.alpha, a1 = axis_vertical ? hc.alpha : a0 + wrap_angle(ha.alpha - a0);
  // direction(Heading{alpha, edge}) with the edge's sine and cosine taken once for all the halvings: the
  // same products, so the same bits.
  const double sin_edge = std::sin(edge), cos_edge = std::cos(edge);
  const auto on_edge = [&](double alpha) { return Vec3(sin_edge * std::cos(alpha), sin_edge * std::sin(alpha), cos_edge); };
  const ConeMembership inside(cone);
  if (inside(on_edge(a0))) return on_edge(a0);
  if (!inside(on_edge(a1))) return on_edge(a1);  // no direction satisfies both: stay near the axis
  const auto point = [&](double t) { return on_edge(a0 + t * (a1 - a0)); };
  // Along the edge, direction . axis = sin(edge) (x cos alpha + y sin alpha) + cos(edge) z.
  const Vec3& x = cone.axis;
  const double q = inside.cos_limit() * x.norm() - cos_edge * x.z();
  const double hi = search_crossing(inside, point, first_crossing(sin_edge * x.x(), sin_edge * x.y(), q, a0, a1 - a0));
  return point(hi);
}

Vec3 first_inside_on_arc(const Cone& cone, const Vec3& from, const Vec3& to) {
  if (cone.contains(from)) return from;
  const double omega = angle_between(from, to);
  if (omega < 1e-12) return to;
  // Spherical interpolation; sin(omega) ~ 0 only for opposite directions, where any great circle will do.
  const Vec3 side = omega > kPi - 1e-9 ? any_perpendicular(from) : Vec3((to - std::cos(omega) * from).normalized());
  const auto at = [&](double t) { return Vec3(std::cos(t * omega) * from + std::sin(t * omega) * side); };
  const ConeMembership inside(cone);
  // Along the arc, at(t) . axis = (from . axis) cos(t omega) + (side . axis) sin(t omega).
  const double q = inside.cos_limit() * cone.axis.norm() * from.norm();
  const double hi = search_crossing(inside, at, first_crossing(from.dot(cone.axis), side.dot(cone.axis), q, 0.0, omega));
  return at(hi).normalized();
}

Directions boundary_crossings(const Cone& a, const Cone& b) {
  // u = x a + y b + z (a x b) with u . a = cos(ha), u . b = cos(hb), |u| = 1 (unit axes).
  const Vec3 n = a.axis.cross(b.axis);
  const double k = a.axis.dot(b.axis), s2 = n.squaredNorm();
  if (s2 < 1e-18) return {};
  const double ca = std::cos(a.half_angle), cb = std::cos(b.half_angle);
  const double x = (ca - cb * k) / s2, y = (cb - ca * k) / s2;
  const Vec3 m = x * a.axis + y * b.axis;
  const double z2 = (1.0 - m.squaredNorm()) / s2;
  if (z2 < -1e-12) return {};
  if (z2 <= 1e-12) return {{m.normalized(), Vec3::Zero()}, 1};
  const double z = std::sqrt(z2);
  return {{Vec3(m + z * n).normalized(), Vec3(m - z * n).normalized()}, 2};
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
