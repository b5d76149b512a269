#pragma once
// Exact distances between points and the obstacle primitives, used to validate maps, to place random
// obstacles with a clearance, and by tests as the analytic reference.

#include <cstdint>
#include <vector>

#include "geometry/vector.hpp"
#include "world/map/map_spec.hpp"
#include "world/map/triangle_mesh.hpp"

namespace peg3d::world {

/// Signed distance from p to the sphere's surface (m): negative inside.
double signed_distance(const Vec3& p, const SphereObstacle& s);
/// Signed distance from p to the capped cylinder's surface (m): negative inside.
double signed_distance(const Vec3& p, const CylinderObstacle& c);

/// Gap between two obstacles' surfaces (m): positive apart, <= 0 when they touch or overlap.
double gap(const SphereObstacle& a, const SphereObstacle& b);
double gap(const SphereObstacle& a, const CylinderObstacle& b);
double gap(const CylinderObstacle& a, const CylinderObstacle& b);

/// True when a vertical ray upwards from p crosses a triangle of the mesh, i.e. p lies under the surface of a
/// height-field mesh.
bool is_below_surface(const TriangleMesh& mesh, const Vec3& p);

/// A mesh's triangles binned by their x-y boxes on a uniform grid (about two per cell), so that
/// is_below_surface visits only the triangles over p's cell instead of all of them. Built once per mesh; read
/// by any number of threads. The answer is is_below_surface's, exactly (the same test on a superset of the
/// triangles that can hold p).
class VerticalRayIndex {
 public:
  VerticalRayIndex() = default;
  explicit VerticalRayIndex(const TriangleMesh& mesh);
  /// is_below_surface(mesh, p) for the mesh the index was built from (every triangle when built empty).
  bool is_below_surface(const TriangleMesh& mesh, const Vec3& p) const;

 private:
  int column(double x) const;
  int row(double y) const;

  double x0_ = 0.0, y0_ = 0.0, x1_ = 0.0, y1_ = 0.0, cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_;      // cell k's triangles are triangles_[start_[k], start_[k + 1])
  std::vector<std::uint32_t> triangles_;
};

}  // namespace peg3d::world
