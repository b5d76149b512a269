#include "geometry/ray.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace peg3d {
namespace {

// The ray's parameter interval [t0, t1] inside the slab lo <= x <= hi along one axis, intersected into
// [enter, leave]; false when the ray runs parallel to the slab outside it.
bool clip_slab(double origin, double direction, double lo, double hi, double& enter, double& leave) {
  if (direction == 0.0) return origin >= lo && origin <= hi;
  double t0 = (lo - origin) / direction, t1 = (hi - origin) / direction;
  if (t0 > t1) std::swap(t0, t1);
  enter = std::max(enter, t0);
  leave = std::min(leave, t1);
  return true;
}

// The entry functions' answer for a ray that never meets the solid.
constexpr double kNever = std::numeric_limits<double>::infinity();

// The first t >= 0 in the clipped interval [enter, leave], kNever when that is empty or behind the origin.
double first_point(double enter, double leave) {
  if (enter > leave || leave < 0.0) return kNever;
  return std::max(enter, 0.0);
}

// An entry within range, else nullopt (a miss too when the range is infinite).
std::optional<double> within(double t, double range) {
  return t < kNever && t <= range ? std::optional<double>(t) : std::nullopt;
}

}  // namespace

double ray_sphere_entry(const Ray& ray, const Vec3& centre, double radius) {
  const Vec3 m = ray.origin - centre;
  const double c = m.squaredNorm() - radius * radius;
  if (c <= 0.0) return 0.0;  // starts inside or on the surface
  const double b = m.dot(ray.direction);
  if (b >= 0.0) return kNever;  // outside and heading away
  const double disc = b * b - c;
  if (disc < 0.0) return kNever;
  // -b - sqrt(disc) loses digits when the ray passes far from the centre; c / (-b + sqrt(disc)) is the same
  // root without the cancellation.
  return c / (-b + std::sqrt(disc));
}

std::optional<double> ray_sphere(const Ray& ray, const Vec3& centre, double radius, double range) {
  return within(ray_sphere_entry(ray, centre, radius), range);
}

double ray_upright_cylinder_entry(const Ray& ray, const Vec3& base, double radius, double height) {
  // The solid is the intersection of the slab base.z <= z <= base.z + height with the infinite round column;
  // the ray's interval in each is exact, and the first point of their intersection is the entry.
  double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
  if (!clip_slab(ray.origin.z(), ray.direction.z(), base.z(), base.z() + height, enter, leave)) return kNever;
  const ColumnCut cut = column_cut(ray, base, radius);
  if (cut.misses()) return kNever;  // parallel to the axis outside the column, or passing it by
  const double a = cut.a, b = cut.b, c = cut.c;
  if (a != 0.0) {  // (parallel to the axis: inside the column all along)
    const double disc = cut.discriminant();
    const double s = std::sqrt(disc);
    // The two roots without cancellation: q = -(b + sign(b) s), roots q / a and c / q.
    const double q = b >= 0.0 ? -(b + s) : -(b - s);
    double t0 = q / a, t1 = q != 0.0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  return first_point(enter, leave);
}

std::optional<double> ray_upright_cylinder(const Ray& ray, const Vec3& base, double radius, double height,
                                           double range) {
  return within(ray_upright_cylinder_entry(ray, base, radius, height), range);
}

std::optional<double> ray_box(const Ray& ray, const Vec3& lo, const Vec3& hi, double range) {
  double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (!clip_slab(ray.origin[k], ray.direction[k], lo[k], hi[k], enter, leave)) return std::nullopt;
  }
  return within(first_point(enter, leave), range);
}

std::optional<double> ray_triangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c, double range) {
  // Moller-Trumbore, both sides, edges included.
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = ray.direction.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0) return std::nullopt;  // in the triangle's plane, or a degenerate triangle
  const double inv = 1.0 / det;
  const Vec3 s = ray.origin - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Vec3 q = s.cross(e1);
  const double v = ray.direction.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = e2.dot(q) * inv;
  if (t < 0.0 || t > range) return std::nullopt;
  return t;
}

std::optional<double> ray_shape(const Ray& ray, const Shape& shape, const Pose& pose, double range) {
  // In the body's frame the shape is centred on the origin and axis-aligned; distances are the same there.
  const Quat to_body = pose.orientation.conjugate();
  const Ray local{to_body * (ray.origin - pose.position), to_body * ray.direction};
  switch (shape.kind) {
    case Shape::Kind::kSphere: return ray_sphere(local, Vec3::Zero(), shape.radius, range);
    case Shape::Kind::kCylinder:
      return ray_upright_cylinder(local, Vec3(0, 0, -0.5 * shape.height), shape.radius, shape.height, range);
    case Shape::Kind::kBox: return ray_box(local, -0.5 * shape.size, 0.5 * shape.size, range);
  }
  return std::nullopt;
}

BoxExit ray_box_exit(const Ray& ray, const Vec3& lo, const Vec3& hi) {
  BoxExit out{std::numeric_limits<double>::infinity(), 0};
  for (int k = 0; k < 3; ++k) {
    const double o = ray.origin[k], d = ray.direction[k];
    if (o < lo[k] || o > hi[k]) return {0.0, 2 * k + (o > hi[k] ? 1 : 0)};
    if (d == 0.0) continue;
    const double t = d > 0.0 ? (hi[k] - o) / d : (lo[k] - o) / d;
    if (t < out.distance) out = {t, 2 * k + (d > 0.0 ? 1 : 0)};
  }
  return out;
}

}  // namespace peg3d
