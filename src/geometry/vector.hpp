#pragma once
// Basic 3D types shared by every module. Geometry is pure: it knows nothing of Bullet, OctoMap or the game.

#include <algorithm>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace peg3d {

/// A point or direction in metres, world frame: x east, y north, z up.
using Vec3 = Eigen::Vector3d;

/// An axis-aligned box [lo, hi] in metres.
struct Box {
  Vec3 lo = Vec3::Zero();  ///< minimum corner (m)
  Vec3 hi = Vec3::Zero();  ///< maximum corner (m); hi >= lo on every axis for a valid box

  Vec3 size() const { return hi - lo; }
  Vec3 center() const { return 0.5 * (lo + hi); }
  bool contains(const Vec3& p) const { return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all(); }
  /// The nearest point of the box.
  Vec3 clamp(const Vec3& p) const { return p.cwiseMax(lo).cwiseMin(hi); }
  /// The box moved inwards by `margin` on every face (may become empty if margin is too large).
  Box shrunk(double margin) const { return {lo.array() + margin, hi.array() - margin}; }
  /// Distance from an inside point to the nearest face (0 on a face, negative outside).
  double inner_distance(const Vec3& p) const {
    return std::min((p - lo).minCoeff(), (hi - p).minCoeff());
  }
};

/// Two unit vectors that complete the unit `axis` to a right-handed orthonormal frame: `up`, the part of world
/// +z perpendicular to the axis (of +x when the axis is vertical), and `side` = axis x up. The frame a sight ray's
/// rim points and a straight way's clearance segments are laid out in.
struct PerpendicularFrame {
  Vec3 up, side;
};
inline PerpendicularFrame perpendicular_frame(const Vec3& axis) {
  Vec3 up = Vec3::UnitZ() - axis.z() * axis;
  if (up.norm() < 1e-9) up = Vec3::UnitX() - axis.x() * axis;
  up.normalize();
  return {up, axis.cross(up)};
}

}  // namespace peg3d
