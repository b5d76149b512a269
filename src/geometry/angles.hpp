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

/// Whether a polar angle keeps the climb limit: theta within [polar_margin, pi - polar_margin]
/// (SteeringConfig::polar_margin).
inline bool within_climb_limit(double theta, double polar_margin) {
  return theta >= polar_margin && theta <= kPi - polar_margin;
}
/// Whether a non-zero direction keeps the climb limit.
inline bool within_climb_limit(const Vec3& d, double polar_margin) {
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
