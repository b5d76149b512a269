#pragma once
// Push mode (game::MoverDynamics::kPush, docs/maps.md): one run's own Bullet dynamics world (world/body_physics)
// over the map's shared static shapes, with the agents in it as kinematic spheres. Every game step is swept in
// the map's physics substeps: each agent moves along its segment at constant velocity, Bullet resolves its
// contacts with the pushable bodies (they are pushed), and after every substep the exact distance of each agent
// to the dynamic bodies near it (the sensor's candidates) says what it touched: a solid body stops it where it
// stood a substep earlier (an agent collision, as in the shared mode); a pushable one is reported as a push,
// once per agent, body and step. Scripted movers are kinematic bodies here too, for the bodies; the agents'
// contacts with them stay the shared timeline's exact ones.
//
// The world is built by every reset, so a run depends only on its map, configuration and seed, never on the
// runs before it or the thread count.

#include <memory>
#include <span>
#include <vector>

#include "geometry/pose.hpp"
#include "world/bodies/body_physics.hpp"
#include "world/bodies/contact.hpp"
#include "world/map/map_spec.hpp"
#include "world/bodies/mover_timeline.hpp"

namespace peg3d::world {

class PushWorld {
 public:
  /// A touch is a gap of at most this (m) plus the agent's travel in one substep: Bullet's contacts act within
  /// a small margin of the surfaces and a substep ahead.
  static constexpr double kTouchTolerance = 1e-2;
  /// The sensor reaches this far (m) beyond an agent's sphere: the bodies' relative travel in one substep.
  static constexpr double kSensorReach = 0.5;

  /// The bodies of `spec` (kept by reference) at t = 0 over `statics`, the map's shared static shapes
  /// (Arena::physics_shapes); `substeps` physics substeps per game step.
  PushWorld(const MapSpec& spec, std::shared_ptr<const StaticPhysicsShapes> statics, int substeps);

  /// Agent i (agents are added in index order) as a sphere of `radius` m at `at`.
  void add_agent(double radius, const Vec3& at);
  /// Agent i leaves the world (captured): it stops pushing and touching.
  void remove_agent(int i);

  /// One game step: agent i moves from from[i] to to[i] over the step (agents removed stand out of the world).
  /// A solid touch sets to[i] to where the agent was a substep earlier; every touch is appended to `touches`
  /// (kind kMover; `pushed` for a pushable body; fraction: the end of the substep it was found at; point: the
  /// body's point nearest the agent's centre), agents in index order, each agent's in time order: at most one
  /// solid touch per agent and one push per agent and body, so touches.reserve(max_touches()) keeps every step
  /// allocation-free.
  void advance(std::span<const Vec3> from, std::span<Vec3> to, std::vector<Contact>& touches);
  /// The most touches a step can report.
  std::size_t max_touches() const { return radius_.size() * (near_.size() + 1); }

  /// The dynamic bodies' point nearest to p now, within `cap` m (the lowest index among equally near ones).
  MoverPoint nearest(const Vec3& p, double cap) const;
  /// Where mover m is now (dynamic bodies as simulated; scripted ones at the current time).
  Pose pose(int m) const;
  int movers() const { return static_cast<int>(spec_.movers.size()); }

 private:
  const MapSpec& spec_;
  std::unique_ptr<BodyPhysics> physics_;
  int substeps_ = 1;
  double h_ = 1.0 / 240.0;
  long substep_ = 0;
  std::vector<double> radius_;
  std::vector<bool> in_world_;
  std::vector<int> near_;               // scratch: the sensor's candidates
  std::vector<bool> stopped_;           // scratch: per agent, stopped by a solid touch this step
  std::vector<int> pushed_;             // scratch: (agent, mover) pairs reported this step, as agent * count + mover
  mutable std::vector<int> candidates_;  // scratch of nearest()
};

}  // namespace peg3d::world
