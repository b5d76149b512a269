#include "geometry/pose.hpp"

#include <algorithm>
#include <cmath>

namespace peg3d {

Pose interpolate(const Pose& a, const Pose& b, double s) {
  return {a.position + s * (b.position - a.position), a.orientation.slerp(s, b.orientation)};
}

double Shape::bounding_radius() const {
  switch (kind) {
    case Kind::kSphere: return radius;
    case Kind::kCylinder: return std::hypot(radius, 0.5 * height);
    case Kind::kBox: return 0.5 * size.norm();
  }
  return radius;
}

const char* to_string(Shape::Kind k) {
  switch (k) {
    case Shape::Kind::kSphere: return "sphere";
    case Shape::Kind::kCylinder: return "cylinder";
    case Shape::Kind::kBox: return "box";
  }
  return "?";
}

namespace {

// p in the body frame of `pose`.
Vec3 to_body(const Pose& pose, const Vec3& p) { return pose.orientation.conjugate() * (p - pose.position); }
Vec3 to_world(const Pose& pose, const Vec3& q) { return pose.orientation * q + pose.position; }

}  // namespace

ShapePoint nearest_on_shape(const Shape& shape, const Pose& pose, const Vec3& p) {
  switch (shape.kind) {
    case Shape::Kind::kSphere: {
      const Vec3 d = p - pose.position;
      const double n = d.norm();
      if (n <= shape.radius) return {0.0, p};
      return {n - shape.radius, pose.position + (shape.radius / n) * d};
    }
    case Shape::Kind::kCylinder: {
      const Vec3 q = to_body(pose, p);
      const double h = 0.5 * shape.height;
      const double rho = std::hypot(q.x(), q.y());
      Vec3 c = q;
      if (rho > shape.radius) c.head<2>() *= shape.radius / rho;
      c.z() = std::clamp(q.z(), -h, h);
      const double d = (q - c).norm();
      return d == 0.0 ? ShapePoint{0.0, p} : ShapePoint{d, to_world(pose, c)};
    }
    case Shape::Kind::kBox: {
      const Vec3 q = to_body(pose, p);
      const Vec3 half = 0.5 * shape.size;
      const Vec3 c = q.cwiseMax(-half).cwiseMin(half);
      const double d = (q - c).norm();
      return d == 0.0 ? ShapePoint{0.0, p} : ShapePoint{d, to_world(pose, c)};
    }
  }
  return {};
}

double signed_distance(const Shape& shape, const Pose& pose, const Vec3& p) {
  const ShapePoint outside = nearest_on_shape(shape, pose, p);
  if (outside.distance > 0.0) return outside.distance;
  switch (shape.kind) {
    case Shape::Kind::kSphere: return (p - pose.position).norm() - shape.radius;
    case Shape::Kind::kCylinder: {
      const Vec3 q = to_body(pose, p);
      return -std::min(shape.radius - std::hypot(q.x(), q.y()), 0.5 * shape.height - std::abs(q.z()));
    }
    case Shape::Kind::kBox: {
      const Vec3 q = to_body(pose, p);
      return -(0.5 * shape.size - q.cwiseAbs()).minCoeff();
    }
  }
  return 0.0;
}

}  // namespace peg3d
