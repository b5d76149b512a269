#include "geometry/plane_section.hpp"

#include <cassert>
#include <cmath>

namespace peg3d {
namespace {

// Sutherland-Hodgman: keeps the part of the convex polygon `in` where x . normal <= offset.
void clip(const std::vector<Vec3>& in, const Vec3& normal, double offset, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = in[i];
    const Vec3& b = in[(i + 1) % n];
    const double da = a.dot(normal) - offset, db = b.dot(normal) - offset;
    if (da <= 0.0) out.push_back(a);
    if ((da <= 0.0) != (db <= 0.0)) out.push_back(a + (da / (da - db)) * (b - a));
  }
}

}  // namespace

void plane_section(const Vec3& point, const Vec3& normal, const Box& box, std::span<const HalfSpace> cuts,
                   std::vector<Vec3>& corners, std::vector<Vec3>& scratch) {
  // A square of the plane about `point` that holds every point of the plane within the box, cut down face by face.
  const auto [u, w] = perpendicular_frame(normal);
  const double r = (point - box.center()).norm() + box.size().norm();
  corners.assign({point + r * (u + w), point + r * (w - u), point - r * (u + w), point + r * (u - w)});
  for (int axis = 0; axis < 3 && !corners.empty(); ++axis) {
    const Vec3 e = Vec3::Unit(axis);
    clip(corners, e, box.hi[axis], scratch), corners.swap(scratch);
    clip(corners, -e, -box.lo[axis], scratch), corners.swap(scratch);
  }
  for (const HalfSpace& h : cuts) {
    if (corners.empty()) break;
    clip(corners, h.normal, h.offset, scratch), corners.swap(scratch);
  }
}

Vec3 polygon_centroid(std::span<const Vec3> corners, const Vec3& normal) {
  assert(!corners.empty());
  // A fan of triangles from the first corner, each weighted by its signed area.
  Vec3 sum = Vec3::Zero();
  double area = 0.0;
  for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
    const double a = 0.5 * (corners[i] - corners[0]).cross(corners[i + 1] - corners[0]).dot(normal);
    sum += a * (corners[0] + corners[i] + corners[i + 1]) / 3.0;
    area += a;
  }
  if (std::abs(area) > 1e-12) return sum / area;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& c : corners) mean += c;
  return mean / double(corners.size());
}

}  // namespace peg3d
