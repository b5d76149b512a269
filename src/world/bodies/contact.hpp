#pragma once
// What an agent touched during a step: one record from the queries that find it (the static sweep of
// world/collision/collision_world.hpp, the movers' timeline of world/bodies/mover_timeline.hpp, push mode's bodies of
// world/bodies/push_world.hpp) to the step's events (game::CollisionEvent, game::PushEvent, which add when and who)
// and the collision log.

#include "geometry/vector.hpp"

namespace peg3d::world {

/// What an agent can touch.
enum class ObstacleKind { kSphere, kCylinder, kMesh, kBoundary, kAgent, kMover };

/// Name of a kind: "sphere", "cylinder", "mesh", "boundary", "agent", "mover".
const char* to_string(ObstacleKind kind);

struct Contact {
  int agent = -1;                             ///< the agent's index; -1 until the game sets it (timeline queries)
  ObstacleKind kind = ObstacleKind::kSphere;  ///< what it touched (never kBoundary: faces are the game's business)
  int obstacle_id = -1;                       ///< index in the map's list of that kind; the other agent's for kAgent
  int triangle = -1;                          ///< triangle within the mesh for kMesh, else -1
  double fraction = 0.0;                      ///< time of impact as a fraction of the step, [0, 1]; 0 for overlaps
  Vec3 point = Vec3::Zero();                  ///< m, on the surface touched
  Vec3 normal = Vec3::UnitZ();                ///< unit, from what was touched towards the agent
  double penetration = 0.0;                   ///< m, >= 0: overlap depth when the agent already intersects
  /// Push mode: a pushable body the agent pushed, which is a push event and not a collision (fraction: the end
  /// of the physics substep it was found at).
  bool pushed = false;
  /// A mover's contact search reached its bound (MoverTimeline::kMaxAdvancementSteps) before it could tell: the
  /// contact is assumed at the last fraction it proved free, where the agent still stood apart.
  bool gave_up = false;
};

}  // namespace peg3d::world
