#pragma once
// The generalized Apollonius surface in 3D (paper section 3.1, eq. 2-3): the points C the evader E and
// the pursuer P reach at the same time, |EC| / |PC| = a with speed ratio a = vE / vP. It is a sphere for
// a != 1 (enclosing E when a < 1, P when a > 1) and the perpendicular bisecting plane of PE for a = 1.

#include <optional>

#include "geometry/vector.hpp"

namespace peg3d {

/// Speed ratios within this distance of 1 are treated as 1 (the sphere degenerates into a plane).
inline constexpr double kUnitRatioTolerance = 1e-9;

struct Sphere {
  Vec3 center = Vec3::Zero();  ///< m
  double radius = 0.0;         ///< m, >= 0
};

struct Plane {
  Vec3 point = Vec3::Zero();   ///< m, a point of the plane
  Vec3 normal = Vec3::UnitX(); ///< unit normal
  double signed_distance(const Vec3& p) const { return normal.dot(p - point); }
};

/// Who reaches a point first when both head straight for it at full speed.
enum class FirstArrival { kPursuer, kEvader, kTie };

class ApolloniusSurface {
 public:
  /// a = vE / vP (dimensionless, finite, > 0). P and E may coincide (the surface is then the point P).
  /// Throws InvalidParameter on a bad ratio or non-finite positions.
  ApolloniusSurface(const Vec3& pursuer, const Vec3& evader, double speed_ratio);

  double speed_ratio() const { return a_; }
  /// True when a = 1 (within kUnitRatioTolerance): the surface is the bisecting plane.
  bool is_plane() const { return is_plane_; }
  /// Eq. (3): center (E - a^2 P) / (1 - a^2), radius |a / (1 - a^2)| |PE|. Only when !is_plane().
  const Sphere& sphere() const { return sphere_; }
  /// The perpendicular bisector of PE, normal pointing from P towards E. Only when is_plane().
  const Plane& plane() const { return plane_; }

  /// Signed arrival-time difference measure |EX| - a |PX| (m): < 0 where the evader arrives first
  /// (its dominance region), > 0 where the pursuer does, 0 on the surface.
  double dominance(const Vec3& x) const { return (x - evader_).norm() - a_ * (x - pursuer_).norm(); }

  /// Who reaches x first; kTie when |dominance| <= tolerance (m).
  FirstArrival first_arrival(const Vec3& x, double tolerance = 1e-12) const;

 private:
  Vec3 pursuer_, evader_;
  double a_;
  bool is_plane_;
  Sphere sphere_;
  Plane plane_;
};

/// The point where a pursuer heading straight for it meets an evader that runs straight along the unit
/// direction `evader_direction` at ratio a = vE / vP: the first s >= 0 with |E + s d - P| = s / a.
/// Returns nothing when the evader is never caught on that line (possible only for a >= 1).
std::optional<Vec3> interception_point(const Vec3& pursuer, const Vec3& evader, const Vec3& evader_direction,
                                       double speed_ratio);

}  // namespace peg3d
