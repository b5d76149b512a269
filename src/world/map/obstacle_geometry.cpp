#include "world/map/obstacle_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace peg3d::world {
namespace {

/// Signed distance from the horizontal offset/vertical offset pair to a disc x interval product: the
/// cylinder is the set {horizontal <= 0, vertical <= 0} of the two slab distances.
double product_distance(double horizontal, double vertical) {
  const double outside = std::hypot(std::max(horizontal, 0.0), std::max(vertical, 0.0));
  const double inside = std::min(std::max(horizontal, vertical), 0.0);
  return outside + inside;
}

double vertical_gap(double lo_a, double hi_a, double lo_b, double hi_b) {
  return std::max(lo_a - hi_b, lo_b - hi_a);
}

}  // namespace

double signed_distance(const Vec3& p, const SphereObstacle& s) { return (p - s.center).norm() - s.radius; }

double signed_distance(const Vec3& p, const CylinderObstacle& c) {
  const double horizontal = std::hypot(p.x() - c.base.x(), p.y() - c.base.y()) - c.radius;
  const double vertical = vertical_gap(p.z(), p.z(), c.base.z(), c.base.z() + c.height);
  return product_distance(horizontal, vertical);
}

double gap(const SphereObstacle& a, const SphereObstacle& b) {
  return (a.center - b.center).norm() - a.radius - b.radius;
}

double gap(const SphereObstacle& a, const CylinderObstacle& b) { return signed_distance(a.center, b) - a.radius; }

double gap(const CylinderObstacle& a, const CylinderObstacle& b) {
  // Both are (disc x interval) products, so the gap is the product of the disc gap and the interval gap.
  const double horizontal = std::hypot(a.base.x() - b.base.x(), a.base.y() - b.base.y()) - a.radius - b.radius;
  const double vertical = vertical_gap(a.base.z(), a.base.z() + a.height, b.base.z(), b.base.z() + b.height);
  return product_distance(horizontal, vertical);
}

namespace {

// Whether the triangle f lies above p: its x-y projection holds p's (x, y) (edges included) and its height
// there is above p.
bool is_above(const TriangleMesh& mesh, const std::array<int, 3>& f, const Vec3& p) {
  const Vec3& a = mesh.vertices[std::size_t(f[0])];
  const Vec3& b = mesh.vertices[std::size_t(f[1])];
  const Vec3& c = mesh.vertices[std::size_t(f[2])];
  // Barycentric coordinates of p's (x, y) in the triangle's projection on the x-y plane.
  const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
  if (std::abs(det) < 1e-15) return false;  // vertical triangle: a vertical ray grazes it
  const double u = ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
  const double v = ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
  if (u < 0.0 || v < 0.0 || u + v > 1.0) return false;
  return a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z()) > p.z();
}

}  // namespace

bool is_below_surface(const TriangleMesh& mesh, const Vec3& p) {
  for (const auto& f : mesh.faces) {
    if (is_above(mesh, f, p)) return true;
  }
  return false;
}

VerticalRayIndex::VerticalRayIndex(const TriangleMesh& mesh) {
  if (mesh.faces.empty()) return;
  const Box b = mesh.bounds();
  x0_ = b.lo.x(), y0_ = b.lo.y(), x1_ = b.hi.x(), y1_ = b.hi.y();
  // About two triangles' boxes per cell on a well-shaped terrain.
  const double w = std::max(b.hi.x() - b.lo.x(), 1e-9), h = std::max(b.hi.y() - b.lo.y(), 1e-9);
  const double cells = std::clamp(double(mesh.faces.size()) / 2.0, 1.0, double(1 << 22));
  cell_ = std::sqrt(w * h / cells);
  nx_ = std::max(1, int(std::ceil(w / cell_)));
  ny_ = std::max(1, int(std::ceil(h / cell_)));
  // Counting sort of the triangles into the cells their x-y boxes overlap.
  std::vector<std::uint32_t> count(std::size_t(nx_) * std::size_t(ny_) + 1, 0);
  const auto for_cells = [&](const std::array<int, 3>& f, auto&& visit) {
    const Vec3& a = mesh.vertices[std::size_t(f[0])];
    const Vec3& p = mesh.vertices[std::size_t(f[1])];
    const Vec3& c = mesh.vertices[std::size_t(f[2])];
    const int i0 = column(std::min({a.x(), p.x(), c.x()})), i1 = column(std::max({a.x(), p.x(), c.x()}));
    const int j0 = row(std::min({a.y(), p.y(), c.y()})), j1 = row(std::max({a.y(), p.y(), c.y()}));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) visit(std::size_t(j) * std::size_t(nx_) + std::size_t(i));
  };
  for (const auto& f : mesh.faces) for_cells(f, [&](std::size_t k) { ++count[k + 1]; });
  for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
  start_ = count;
  triangles_.resize(count.back());
  for (std::size_t t = 0; t < mesh.faces.size(); ++t) {
    for_cells(mesh.faces[t], [&](std::size_t k) { triangles_[count[k]++] = std::uint32_t(t); });
  }
}

bool VerticalRayIndex::is_below_surface(const TriangleMesh& mesh, const Vec3& p) const {
  if (start_.empty()) return world::is_below_surface(mesh, p);  // no index: every triangle
  if (!(p.x() >= x0_ && p.x() <= x1_ && p.y() >= y0_ && p.y() <= y1_)) return false;  // outside every box
  // column() and row() are the binning's: a triangle whose box holds p's (x, y) was binned into p's cell.
  const std::size_t k = std::size_t(row(p.y())) * std::size_t(nx_) + std::size_t(column(p.x()));
  for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i) {
    if (is_above(mesh, mesh.faces[triangles_[i]], p)) return true;
  }
  return false;
}

int VerticalRayIndex::column(double x) const { return std::clamp(int(std::floor((x - x0_) / cell_)), 0, nx_ - 1); }
int VerticalRayIndex::row(double y) const { return std::clamp(int(std::floor((y - y0_) / cell_)), 0, ny_ - 1); }

}  // namespace peg3d::world
