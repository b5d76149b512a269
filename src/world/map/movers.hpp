#pragma once
// Scripted motion of moving obstacles: where a path or orbit mover is at any time, exactly. (Dynamic bodies
// are simulated: world/bodies/mover_timeline.hpp.)

#include <string>
#include <vector>

#include "geometry/pose.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::world {

/// Orientation from rotations about the fixed world axes, x first, then y, then z (degrees), as for terrain.
Quat orientation_deg(const Vec3& rotation_deg);

/// The centre of a path mover at time t (s, >= 0): arc length speed * t along the waypoints, wrapping to the
/// first waypoint (loop) or turning back at the last and the first (back and forth).
Vec3 path_position(const PathMotion& path, double t);

/// The centre of an orbit mover at time t (s): center + radius (cos w u + sin w v), w = phase + 2 pi t / period,
/// u the unit direction of +x projected on the orbit's plane (+y when the axis is along x), v = axis x u.
Vec3 orbit_position(const OrbitMotion& orbit, double t);

/// std::fmod(x, y) to the bit for finite x >= 0 and y > 0, without the library's bit-by-bit loop: the quotient's
/// whole part n from a division, x - n y exactly (the product split into two doubles, Dekker's product; the
/// difference is exact by Sterbenz's lemma), n corrected by one when the division rounded across a whole number.
double exact_remainder(double x, double y);

/// A path or orbit mover prepared for evaluation at many times: what depends only on the mover (its
/// orientation, an orbit's plane, a path's segment lengths) computed once and kept here with the motion's own
/// numbers (queries read this object alone), the rest by the same arithmetic as path_position and
/// orbit_position, so that pose(t) is scripted_pose(mover, t) to the bit.
class ScriptedMotion {
 public:
  explicit ScriptedMotion(const MoverSpec& mover);
  Pose pose(double t) const { return {position(t), orientation_}; }
  /// pose(t).position.
  Vec3 position(double t) const;

 private:
  bool orbit_ = false;
  Quat orientation_;
  // Orbits: centre + radius (cos w u + sin w v), w = phase + 2 pi t / period.
  Vec3 center_ = Vec3::Zero(), u_ = Vec3::Zero(), v_ = Vec3::Zero();
  double radius_ = 0.0, period_ = 1.0, phase_ = 0.0;
  // Paths: arc length speed t along the waypoints.
  std::vector<Vec3> waypoints_;
  std::vector<double> lengths_;  ///< segment i's length, waypoint i to i + 1
  double speed_ = 0.0, open_ = 0.0, closing_ = 0.0, cycle_ = 0.0;
  bool loop_ = true;
};

/// The pose of a path or orbit mover at time t; its orientation stays as given.
Pose scripted_pose(const MoverSpec& mover, double t);

/// An upper bound on how fast a path or orbit mover's centre moves, m/s.
double scripted_speed(const MoverSpec& mover);

/// Points along a scripted mover's whole route, at most `spacing` m apart (paths: every segment; orbits: the
/// circle); for a dynamic body its start only.
std::vector<Vec3> route_samples(const MoverSpec& mover, double spacing);

/// The world's obstacle kind of movers' contacts is ObstacleKind::kMover; this names a mover in messages:
/// "sphere mover 3 (path)".
std::string describe_mover(const MoverSpec& mover, int id);

}  // namespace peg3d::world
