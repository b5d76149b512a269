#include "geometry/half_spaces.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace peg3d {

Vec3 nearest_within(const Vec3& m, std::span<const HalfSpace> h) {
  // Rounding of the projections leaves the points on a plane a hair outside it.
  constexpr double kTolerance = 1e-12;
  // Planes closer to parallel than this meet far away or not at all; the other candidates cover them.
  constexpr double kParallel = 1e-9;
  auto inside = [&](const Vec3& v) {
    return std::all_of(h.begin(), h.end(), [&](const HalfSpace& s) { return v.dot(s.normal) <= s.offset + kTolerance; });
  };
  if (inside(m)) return m;
  Vec3 best = Vec3::Zero();
  assert(inside(best));
  double best_distance = m.squaredNorm();
  auto consider = [&](const Vec3& v) {
    const double d = (v - m).squaredNorm();
    if (d < best_distance && inside(v)) best = v, best_distance = d;
  };
  const std::size_t n = h.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double excess = m.dot(h[i].normal) - h[i].offset;
    if (excess > 0.0) consider(m - excess * h[i].normal);
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec3& a = h[i].normal;
      const Vec3& b = h[j].normal;
      const Vec3 u = a.cross(b);
      const double length2 = u.squaredNorm();
      if (length2 < kParallel) continue;
      // The line's point in the plane of the two normals: x a + y b with a . p = offset_i, b . p = offset_j.
      const double c = a.dot(b);
      const double x = (h[i].offset - c * h[j].offset) / length2, y = (h[j].offset - c * h[i].offset) / length2;
      const Vec3 p = x * a + y * b;
      consider(p + (m - p).dot(u) / length2 * u);
      for (std::size_t k = j + 1; k < n; ++k) {
        const Vec3& e = h[k].normal;
        const double det = e.dot(u);
        if (std::abs(det) < kParallel) continue;
        consider((h[i].offset * b.cross(e) + h[j].offset * e.cross(a) + h[k].offset * u) / det);
      }
    }
  }
  return best;
}

}  // namespace peg3d
