#pragma once
// Where every moving obstacle of a map is, at any time of a game. Scripted movers (paths, orbits) are exact
// functions of time. Dynamic bodies are simulated once by a Bullet dynamics world (btDiscreteDynamicsWorld,
// double precision) at the map's physics rate, with the static obstacles, the terrain, the arena's faces and
// the scripted movers (kinematic bodies that push and are never pushed), and their pose at every substep is
// kept. Agents do not enter this simulation: they never push a body (a contact stops the agent instead), so
// the motion of every mover depends on the map alone, is computed once per map and shared read-only by all
// runs and threads, and every run sees the same physical world from the same start.
//
// The module also answers the two questions the game asks of movers at a time t: the nearest point of any
// mover to a point (exact, per shape), and the first contact of an agent's sphere moving along a segment
// during a game step with any mover, by conservative advancement on exact distances (no tunnelling at any
// relative speed).

#include <memory>
#include <optional>
#include <vector>

#include "geometry/pose.hpp"
#include "world/map_spec.hpp"
#include "world/triangle_mesh.hpp"

namespace peg3d::world {

/// A mover's point nearest to a query point, at some time.
struct MoverPoint {
  int mover = -1;             ///< index in MapSpec::movers; -1 when none is within the cap
  double distance = 0.0;      ///< m, >= 0 (0 inside the mover)
  Vec3 point = Vec3::Zero();  ///< the mover's point nearest to the query
};

/// The first touch of an agent's sphere with a mover during one step.
struct MoverContact {
  int mover = -1;
  double fraction = 0.0;         ///< of the step, in [0, 1]
  Vec3 point = Vec3::Zero();     ///< m, on the mover's surface
  Vec3 normal = Vec3::UnitZ();   ///< unit, from the mover towards the agent
  double penetration = 0.0;      ///< m, when already overlapping at the start of the step
};

class MoverTimeline {
 public:
  /// Contacts closer than this count as touching (m): it bounds conservative advancement's work.
  static constexpr double kContactTolerance = 1e-4;

  /// Simulates the map's movers from 0 to at least `duration` s (scripted movers need no simulation).
  /// `meshes` are the map's placed terrain meshes, in spec.meshes' order.
  MoverTimeline(const MapSpec& spec, const std::vector<TriangleMesh>& meshes, double duration);

  int count() const { return static_cast<int>(movers_.size()); }
  const MoverSpec& mover(int m) const { return movers_[std::size_t(m)]; }
  /// s, the time the dynamic bodies were simulated to; past it they stay where they were.
  double duration() const { return duration_; }
  int rate_hz() const { return rate_hz_; }

  /// The pose of mover m at time t (s): exact for scripted movers; for dynamic bodies interpolated between the
  /// simulated substeps (positions linearly, orientations spherically).
  Pose pose(int m, double t) const;

  /// The movers' point nearest to p at time t, if any lies within `cap` m. No allocation.
  MoverPoint nearest(const Vec3& p, double t, double cap) const;

  /// The first contact, during the step [t0, t0 + dt], of a sphere of `radius` moving from `from` to `to` at
  /// constant velocity with any mover; nullopt when it touches none. No allocation.
  std::optional<MoverContact> first_contact(const Vec3& from, const Vec3& to, double radius, double t0,
                                            double dt) const;

  /// The largest distance any point of mover m moves during [t0, t1] (a bound, m).
  double travel_bound(int m, double t0, double t1) const;

 private:
  std::vector<MoverSpec> movers_;
  std::vector<int> dynamic_index_;   ///< per mover: its row in poses_, or -1 for scripted ones
  std::vector<std::vector<Pose>> poses_;  ///< per dynamic body: pose at every substep 0..substeps
  double duration_ = 0.0;
  int rate_hz_ = 240;
  long substeps_ = 0;
};

}  // namespace peg3d::world
