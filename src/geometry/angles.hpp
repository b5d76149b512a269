#pragma once
// Angles and headings in 3D. A heading is the paper's pair (alpha, theta): alpha is the azimuth of the
// velocity's projection on the x-y plane measured from +x, theta the polar angle from +z (paper eq. 1).

#include <cmath>
#include <numbers>

#include "geometry/vector.hpp"

namespace peg3d {

inline constexpr double kPi = std::numbers::pi;

/// Wraps an angle to (-pi, pi].
inline double wrap_angle(double a) {
  // std::remainder(a, 2 pi), bit for bit, without the library call for |a| < 9 (every angle a step makes):
  // there the rounded quotient is 0 or +-1, and for pi < |a| < 9 the difference a -+ 2 pi is exact
  // (Sterbenz: 2 pi / 2 <= |a| <= 2 * 2 pi). Beyond, and for NaN and infinities, the library.
  constexpr double kTwoPi = 2.0 * kPi;
  const double m = std::abs(a);
  if (m <= kPi) {
    // as it is
  } else if (m < 9.0) {
    const double wrapped = a - std::copysign(kTwoPi, a);
    a = wrapped == 0.0 ? std::copysign(0.0, a) : wrapped;  // a zero remainder keeps the sign of a
  } else {
    a = std::remainder(a, kTwoPi);  // in [-pi, pi]
  }
  return a == -kPi ? kPi : a;
}

/// A heading: azimuth alpha in (-pi, pi] (rad) and polar angle theta in [0, pi] (rad).
struct Heading {
  double alpha = 0.0;        ///< rad, angle of the x-y projection from +x, wrapped to (-pi, pi]
  double theta = kPi / 2.0;  ///< rad, angle from +z, in [0, pi]; pi/2 is level flight
};

/// Unit velocity direction of a heading: (sin th cos al, sin th sin al, cos th).
inline Vec3 direction(const Heading& h) {
  const double s = std::sin(h.theta);
  return {s * std::cos(h.alpha), s * std::sin(h.alpha), std::cos(h.theta)};
}

/// Heading of a non-zero direction. A vertical direction gets alpha = 0.
inline Heading heading_of(const Vec3& d) {
  const double horizontal = std::hypot(d.x(), d.y());
  return {horizontal > 0.0 ? std::atan2(d.y(), d.x()) : 0.0, std::atan2(horizontal, d.z())};
}

/// cos(x) for x in [0, pi] to within 1e-11, by a polynomial: for decisions taken with a margin far wider than
/// that (cosine tests that fall back to the exact angle near the boundary), never as a value.
inline double rough_cos(double x) {
  // cos(x) = -sin(u) with u = x - pi/2 in [-pi/2, pi/2]: Taylor to u^15, whose remainder is below
  // (pi/2)^17 / 17! = 6.2e-12.
  const double u = x - 0.5 * kPi, v = u * u;
  double p = -1.0 / 1307674368000.0;
  for (const double c : {1.0 / 6227020800.0, -1.0 / 39916800.0, 1.0 / 362880.0, -1.0 / 5040.0, 1.0 / 120.0,
                         -1.0 / 6.0, 1.0}) {
    p = p * v + c;
  }
  return -u * p;
}

/// Whether a polar angle keeps the climb limit: theta within [polar_margin, pi - polar_margin]
/// (SteeringConfig::polar_margin).
inline bool within_climb_limit(double theta, double polar_margin) {
  return theta >= polar_margin && theta <= kPi - polar_margin;
}
/// Whether a non-zero direction keeps the climb limit: within_climb_limit(heading_of(d).theta), the same answer.
inline bool within_climb_limit(const Vec3& d, double polar_margin) {
  // |cos theta| = |z| / |d| against cos(polar_margin) decides all but the directions within about 1e-9 rad of
  // the limit (theta moves at least as much as its cosine); those take the exact polar angle.
  const double n2 = d.squaredNorm();
  if (n2 > 0.0 && std::isfinite(n2) && polar_margin >= 0.0 && polar_margin < 0.5 * kPi) {
    const double c = std::abs(d.z()) / std::sqrt(n2), limit = rough_cos(polar_margin);
    if (c < limit - 1e-9) return true;
    if (c > limit + 1e-9) return false;
  }
  return within_climb_limit(heading_of(d).theta, polar_margin);
}

/// Signed errors that turn a heading towards a direction: d_alpha = wrap(azimuth(d) - alpha) in (-pi, pi] and
/// d_theta = polar(d) - theta in [-pi, pi]. Steering by exactly these errors points the heading along d. A
/// vertical d has no azimuth; its azimuth error is 0.
struct AngleErrors {
  double azimuth = 0.0;    ///< rad
  double elevation = 0.0;  ///< rad (positive: the direction is further from +z than the heading)
};

inline AngleErrors angle_errors(const Heading& h, const Vec3& d) {
  const Heading t = heading_of(d);
  const bool vertical = d.x() == 0.0 && d.y() == 0.0;
  return {vertical ? 0.0 : wrap_angle(t.alpha - h.alpha), t.theta - h.theta};
}

/// Unsigned angle between two non-zero vectors in [0, pi]; atan2 form stays accurate near 0 and pi.
inline double angle_between(const Vec3& u, const Vec3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); }

}  // namespace peg3d
