#pragma once
// Collision detection for agents moving through an Arena, with Bullet (double precision). Obstacles are
// static Bullet shapes (btSphereShape, btCylinderShapeZ, btBvhTriangleMeshShape over the Arena's triangles) in
// the broadphase; agents are kinematic spheres tested with explicit queries (convexSweepTest, contactTest)
// whose filters accept every obstacle and no agent. Every move is a swept-sphere test from the old to the new
// position, so no step is long enough to tunnel through a thin obstacle.
//
// A CollisionWorld is mutable scratch for one thread (Bullet's broadphase keeps a shared ray-test stack); build
// one per thread or per run from the shared, const Arena. Bullet types stay in the .cpp.

#include <memory>
#include <optional>
#include <span>

#include "geometry/vector.hpp"
#include "world/arena.hpp"

namespace peg3d::world {

/// A static obstacle's surface point near a query point (CollisionWorld::obstacles_near).
struct NearPoint {
  Vec3 point = Vec3::Zero();                  ///< m, on the obstacle's surface, nearest to the query point
  double distance = 0.0;                      ///< m, >= 0, from the query point to `point`
  ObstacleKind kind = ObstacleKind::kSphere;  ///< kSphere, kCylinder or kMesh
  int obstacle_id = -1;                       ///< index into MapSpec::spheres / cylinders / meshes by kind
  int triangle = -1;                          ///< triangle index within the mesh for kMesh, else -1
};

/// Options of a CollisionWorld.
struct CollisionOptions {
  /// Skip the Bullet sweep when the distance field proves the move cannot reach an obstacle. Never changes an
  /// answer (tests compare against always sweeping); off only for testing and benchmarking.
  bool distance_early_out = true;
};

class CollisionWorld {
 public:
  explicit CollisionWorld(std::shared_ptr<const Arena> arena, const CollisionOptions& options = {});
  ~CollisionWorld();
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;
  CollisionWorld(CollisionWorld&&) noexcept;
  CollisionWorld& operator=(CollisionWorld&&) noexcept;

  /// Adds a kinematic sphere of `radius` m (> 0) at the origin; returns its index 0, 1, ...
  int add_agent(double radius);
  /// Changes an agent's radius (m, > 0) without allocating (a pool of agents reused across scenarios).
  void set_agent_radius(int agent, double radius);
  /// Teleports an agent without any check (use overlap() to test the new place).
  void place_agent(int agent, const Vec3& p);
  /// Sweeps the agent's sphere from its position to `to`. On a hit the agent stops at the time of impact, a
  /// hair before touching (Bullet stops within 1 mm of contact; the agent is set back 1 mm more along its
  /// path), and the contact is returned; otherwise it ends at `to`. An agent already overlapping an obstacle
  /// is stopped (fraction 0, with the penetration) unless it moves out of it. Agents never collide with each
  /// other; a zero-length move reports nothing. No allocation.
  std::optional<Contact> move_agent(int agent, const Vec3& to);
  /// The deepest overlap of the agent's sphere with an obstacle at its current position, if any.
  std::optional<Contact> overlap(int agent) const;

  /// The static obstacles whose surface lies within `range` m (> 0) of p, exactly (Bullet's closest points, not
  /// the voxel field): a sphere's or cylinder's nearest surface point, and a mesh's nearest point on each of
  /// its triangles within range. Writes the nearest out.size() of them to `out`, nearest first (ties in
  /// kind, obstacle and triangle order), and returns how many it wrote. Moving obstacles do not count. No
  /// allocation.
  int obstacles_near(const Vec3& p, double range, std::span<NearPoint> out);

  Vec3 agent_position(int agent) const;
  int agent_count() const;
  const Arena& arena() const;

  /// Bullet sweeps run so far (moves not settled by the distance field), for tests and benchmarks.
  long long sweep_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace peg3d::world
