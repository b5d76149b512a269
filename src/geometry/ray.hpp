#pragma once
// Where a ray first meets a solid, exactly, in double precision: the distances a range sensor reads (issue 38).
// A ray is an origin and a unit direction; it meets a solid at the smallest distance t in [0, range] at which
// its point lies in the solid (surface included). So a ray that starts inside a solid meets it at t = 0, a ray
// that only touches a solid (a tangent, an edge, a corner) meets it at the touching point, and a ray that lies
// in a face's plane meets the face where it enters it.

#include <optional>

#include "geometry/pose.hpp"
#include "geometry/vector.hpp"

namespace peg3d {

/// A ray: origin (m) and unit direction.
struct Ray {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();  ///< unit length

  Vec3 at(double t) const { return origin + t * direction; }
};

/// The first distance in [0, range] at which the ray meets a solid ball; nullopt when it does not.
std::optional<double> ray_sphere(const Ray& ray, const Vec3& centre, double radius, double range);
/// ray_sphere without a range: the first distance >= 0, +infinity when the ray never meets the ball. For callers
/// that test many solids a ray: an optional's round trip through the stack cost more than the test.
double ray_sphere_entry(const Ray& ray, const Vec3& centre, double radius);

/// The ray's line against the infinite round column of `radius` about the vertical line through `base`, in the
/// terms of t's quadratic a t^2 + 2 b t + c = 0 (a = 0: the ray runs parallel to the axis). ray_upright_cylinder
/// starts from it, so a caller with many cylinders can skip one whose column the ray misses, at no cost in
/// exactness: misses() is true exactly when ray_upright_cylinder would find no root.
struct ColumnCut {
  double a = 0.0, b = 0.0, c = 0.0;
  double discriminant() const { return b * b - a * c; }
  bool misses() const { return a == 0.0 ? c > 0.0 : discriminant() < 0.0; }
};
inline ColumnCut column_cut(const Ray& ray, const Vec3& base, double radius) {
  const double ox = ray.origin.x() - base.x(), oy = ray.origin.y() - base.y();
  const double dx = ray.direction.x(), dy = ray.direction.y();
  return {dx * dx + dy * dy, ox * dx + oy * dy, ox * ox + oy * oy - radius * radius};
}

/// ... a solid upright cylinder: axis +z from the centre of its base disc, `height` long (m).
std::optional<double> ray_upright_cylinder(const Ray& ray, const Vec3& base, double radius, double height,
                                           double range);
/// ray_upright_cylinder without a range: the first distance >= 0, +infinity when never (as ray_sphere_entry).
double ray_upright_cylinder_entry(const Ray& ray, const Vec3& base, double radius, double height);

/// ... a solid axis-aligned box [lo, hi].
std::optional<double> ray_box(const Ray& ray, const Vec3& lo, const Vec3& hi, double range);

/// ... a triangle, from either side; a ray in the triangle's plane does not meet it (a sensor does not see a
/// face edge-on).
std::optional<double> ray_triangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c, double range);

/// ... a posed shape (geometry/pose.hpp: a ball, a cylinder along the body's z centred on its origin, a box).
std::optional<double> ray_shape(const Ray& ray, const Shape& shape, const Pose& pose, double range);

/// Where a ray from inside the box [lo, hi] leaves it: the distance (0 from outside) and the face, 0..5 for
/// -x, +x, -y, +y, -z, +z (the first of them when it leaves through an edge or a corner): what a sensor reads
/// when the arena's faces are walls.
struct BoxExit {
  double distance = 0.0;  ///< m
  int face = 0;
};
BoxExit ray_box_exit(const Ray& ray, const Vec3& lo, const Vec3& hi);

}  // namespace peg3d
