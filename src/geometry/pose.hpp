#pragma once
// Rigid poses and the convex shapes of moving obstacles: the exact distance from a point to a posed sphere,
// upright cylinder or box, and a bound on how far a shape reaches from its centre.

#include <Eigen/Geometry>

#include "geometry/vector.hpp"

namespace peg3d {

using Quat = Eigen::Quaterniond;

/// Where a body is: the position of its centre (m) and its orientation (body to world).
struct Pose {
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
};

/// Linear interpolation of the position and spherical interpolation of the orientation, s in [0, 1].
Pose interpolate(const Pose& a, const Pose& b, double s);

/// A convex shape centred on its body's origin: a ball, a cylinder along the body's z axis, or a box.
struct Shape {
  enum class Kind { kSphere, kCylinder, kBox };
  Kind kind = Kind::kSphere;
  double radius = 1.0;       ///< m, spheres and cylinders, > 0
  double height = 1.0;       ///< m, cylinders: full length along the body's z, > 0
  Vec3 size = Vec3::Ones();  ///< m, boxes: full edge lengths along the body's x, y, z, each > 0

  /// The largest distance from the centre to a point of the shape, m.
  double bounding_radius() const;
};

const char* to_string(Shape::Kind k);

/// The point of a posed shape nearest to p and its distance (0 when p lies inside).
struct ShapePoint {
  double distance = 0.0;      ///< m, >= 0
  Vec3 point = Vec3::Zero();  ///< the shape's point nearest to p (p itself inside)
};

/// Exact nearest point of the shape at `pose` to p.
ShapePoint nearest_on_shape(const Shape& shape, const Pose& pose, const Vec3& p);

/// Signed distance from p to the posed shape's surface: negative inside (exact for spheres; for cylinders and
/// boxes the depth inside is the distance to the nearest face).
double signed_distance(const Shape& shape, const Pose& pose, const Vec3& p);

}  // namespace peg3d
