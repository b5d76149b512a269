#pragma once
// The Bullet dynamics world of a map's moving bodies (btDiscreteDynamicsWorld, double precision): the map's
// static obstacles, terrain and (when physical) arena faces as static bodies, scripted movers as kinematic
// bodies that push and are never pushed, dynamic bodies as rigid bodies, stepped at the map's physics rate.
// Two users: the shared timeline (world/bodies/mover_timeline.hpp) steps one without agents, once per map; push mode
// (world/bodies/push_world.hpp) gives every run one of its own with the agents in it as kinematic spheres. Both build
// it the same way but for one solver setting: push mode separates overlapping bodies by split impulse, which
// moves positions without adding velocity, so that a hit leaves at the speed restitution gives whatever the
// phase of the substep it lands in; the shared timeline keeps Bullet's default (shallow overlaps corrected
// through velocity), so its motion is what it always was. Bodies no agent touches therefore move in push mode
// as in a world without agents, not as in the shared timeline.
//
// In push mode the bodies carry collision groups by what an agent's touch means (DynamicMotion::Touch): an
// agent's kinematic sphere collides with pushable bodies only, and pushes them as Bullet resolves the contact
// (its restitution is 1 and its friction 0, so that a contact's combined values are the body's restitution
// and no friction); a sensor around it (a ghost object, no contact response) reports the dynamic bodies near
// it, solid or pushable, for the game's exact tests. The groups are bits added to Bullet's default ones, so
// the bodies' contacts among themselves are those of the shared world.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "geometry/vector.hpp"
#include "geometry/pose.hpp"
#include "world/map/map_spec.hpp"
#include "world/map/triangle_mesh.hpp"

namespace peg3d::world {

/// Bullet's shapes of a map's static geometry (obstacles, terrain hierarchies with their internal-edge
/// information, face planes), built once and shared read-only by every BodyPhysics over the map, in any thread.
struct StaticPhysicsShapes;

/// The shapes of `spec`'s static geometry over `meshes` (the map's placed terrain meshes, in spec.meshes' order,
/// kept by reference: Bullet reads their arrays in place).
std::shared_ptr<const StaticPhysicsShapes> make_static_physics_shapes(const MapSpec& spec,
                                                                      const std::vector<TriangleMesh>& meshes);

class BodyPhysics {
 public:
  /// A world of `statics` and the movers of `movers` (kept by reference), with `spec`'s gravity. `push` gives
  /// the dynamic bodies their touch groups and allows agents.
  BodyPhysics(const MapSpec& spec, std::shared_ptr<const StaticPhysicsShapes> statics,
              const std::vector<MoverSpec>& movers, bool push = false);
  ~BodyPhysics();
  BodyPhysics(const BodyPhysics&) = delete;
  BodyPhysics& operator=(const BodyPhysics&) = delete;

  /// Moves the scripted movers to their poses at `t_next` (s) and steps the world by h (s). Without agents, once
  /// every dynamic body sleeps in a world without scripted movers nothing can wake one: the world holds still,
  /// to the bit, and is no longer stepped.
  void step(double t_next, double h);

  Pose pose(std::size_t mover) const;
  Vec3 velocity(std::size_t mover) const;  ///< m/s, a dynamic body's linear velocity (0 for scripted movers)

  /// Push mode: an agent's kinematic sphere of `radius` (m) at `at`, and its sensor reaching `reach` m beyond
  /// its surface. Returns the agent's index (0, 1, ... in the order added).
  int add_agent(double radius, const Vec3& at, double reach);
  /// Where agent a is at the end of the next step(); Bullet gives its sphere the velocity of that move.
  void move_agent(int a, const Vec3& at);
  /// Takes agent a out of the world (it stops pushing and sensing).
  void remove_agent(int a);
  /// The dynamic bodies (mover indices, ascending) whose bounds overlapped agent a's sensor in the last step,
  /// at most out.size(); returns how many there were (more than out.size() when they did not fit).
  int bodies_near_agent(int a, std::span<int> out) const;
  /// The dynamic bodies (mover indices, appended in no particular order) whose current bounds overlap `box`.
  void bodies_in(const Box& box, std::vector<int>& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace peg3d::world
