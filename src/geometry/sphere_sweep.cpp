#include "geometry/sphere_sweep.hpp"

#include <cmath>

namespace peg3d {

std::optional<double> first_contact(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double reach) {
  // Relative position p(t) = p + t v; touching means |p + t v|^2 <= reach^2, a quadratic in t.
  const Vec3 p = a0 - b0;
  const Vec3 v = (a1 - a0) - (b1 - b0);
  const double c = p.squaredNorm() - reach * reach;
  if (c <= 0.0) return 0.0;
  const double a = v.squaredNorm();
  const double b = p.dot(v);  // half the linear coefficient
  if (a == 0.0 || b >= 0.0) return std::nullopt;  // not approaching
  const double disc = b * b - a * c;
  if (disc < 0.0) return std::nullopt;  // the closest approach stays outside reach
  // The smaller root, written to avoid cancellation: t = c / (-b + sqrt(disc)).
  const double t = c / (-b + std::sqrt(disc));
  if (t > 1.0) return std::nullopt;
  return t;
}

}  // namespace peg3d
