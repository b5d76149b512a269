#pragma once
// Exact distances between points and the obstacle primitives, used to validate maps, to place random
// obstacles with a clearance, and by tests as the analytic reference.

#include "geometry/vector.hpp"
#include "world/map_spec.hpp"
#include "world/triangle_mesh.hpp"

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

}  // namespace peg3d::world
