#include "world/obstacle_geometry.hpp"

#include <algorithm>
#include <cmath>

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

bool is_below_surface(const TriangleMesh& mesh, const Vec3& p) {
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3& b = mesh.vertices[f[1]];
    const Vec3& c = mesh.vertices[f[2]];
    // Barycentric coordinates of p's (x, y) in the triangle's projection on the x-y plane.
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(det) < 1e-15) continue;  // vertical triangle: a vertical ray grazes it
    const double u = ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
    const double v = ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) continue;
    const double z = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
    if (z > p.z()) return true;
  }
  return false;
}

}  // namespace peg3d::world
