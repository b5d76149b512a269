#include "geometry/apollonius.hpp"

#include <cmath>

#include "core/validation.hpp"

namespace peg3d {
namespace {

void require_finite_point(const char* name, const Vec3& p) {
  for (int i = 0; i < 3; ++i) require_finite(name, p[i]);
}

}  // namespace

ApolloniusSurface::ApolloniusSurface(const Vec3& pursuer, const Vec3& evader, double speed_ratio)
    : pursuer_(pursuer), evader_(evader), a_(speed_ratio) {
  require_finite_point("pursuer", pursuer);
  require_finite_point("evader", evader);
  require_positive("speed_ratio", speed_ratio);
  is_plane_ = std::abs(a_ - 1.0) <= kUnitRatioTolerance;
  if (is_plane_) {
    const Vec3 pe = evader_ - pursuer_;
    const double n = pe.norm();
    plane_.point = 0.5 * (pursuer_ + evader_);
    plane_.normal = n > 0.0 ? Vec3(pe / n) : Vec3::UnitX();
  } else {
    const double k = 1.0 - a_ * a_;
    sphere_.center = (evader_ - a_ * a_ * pursuer_) / k;
    sphere_.radius = std::abs(a_ / k) * (pursuer_ - evader_).norm();
  }
}

FirstArrival ApolloniusSurface::first_arrival(const Vec3& x, double tolerance) const {
  const double d = dominance(x);
  if (std::abs(d) <= tolerance) return FirstArrival::kTie;
  return d < 0.0 ? FirstArrival::kEvader : FirstArrival::kPursuer;
}

std::optional<Vec3> interception_point(const Vec3& pursuer, const Vec3& evader, const Vec3& evader_direction,
                                       double speed_ratio) {
  require_positive("speed_ratio", speed_ratio);
  const Vec3 d = evader_direction.normalized();
  const Vec3 w = evader - pursuer;
  // |w + s d|^2 = s^2 / a^2  <=>  A s^2 + B s + C = 0 with
  const double A = 1.0 - 1.0 / (speed_ratio * speed_ratio);
  const double B = 2.0 * d.dot(w);
  const double C = w.squaredNorm();
  if (C == 0.0) return evader;  // already together
  double s = -1.0;
  if (std::abs(A) <= 1e-12) {
    if (B < 0.0) s = -C / B;  // a = 1: linear equation, a root ahead only when running towards P
  } else {
    const double disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      // Stable roots: q = -(B + sign(B) r) / 2, roots q / A and C / q.
      const double q = -0.5 * (B + std::copysign(r, B));
      const double r1 = q / A;
      const double r2 = q != 0.0 ? C / q : r1;
      const double lo = std::min(r1, r2), hi = std::max(r1, r2);
      s = lo >= 0.0 ? lo : hi;  // the first non-negative root
    }
  }
  if (!(s >= 0.0)) return std::nullopt;
  return Vec3(evader + s * d);
}

}  // namespace peg3d
