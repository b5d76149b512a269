#pragma once
// What a ray meets in the world at an instant: the static scene's solids and the movers where they are then
// (scripted movers exactly, dynamic bodies as the timeline stores them, or as a push-mode run moved them), and
// other spheres (the agents).

#include <span>

#include "geometry/ray.hpp"
#include "sense/static_ray_scene.hpp"
#include "world/bodies/mover_timeline.hpp"
#include "world/bodies/push_world.hpp"

namespace peg3d::sense {

/// The first solid along the ray within `range` at time t (s): the static scene's or a mover's (`movers` null:
/// a map without movers). A static solid and a mover met at one distance: the static one.
RayHit cast_at(const StaticRayScene& scene, const world::MoverTimeline* movers, double t, const Ray& ray, double range);

/// A ball a ray may meet besides the map's solids (an agent's sphere).
struct Ball {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;  ///< m; 0: not in the world (a captured agent)
};

/// Everything a ray meets at one instant.
struct WorldAtInstant {
  const StaticRayScene* scene = nullptr;          ///< the map's static solids (required)
  const world::MoverTimeline* movers = nullptr;   ///< the timeline's movers (null: none)
  double time = 0.0;                              ///< s, the instant the movers are met at
  const world::PushWorld* push = nullptr;         ///< push mode: the run's dynamic bodies where they are now
  const world::MapSpec* map = nullptr;            ///< the push world's map (their shapes), with `push`
  std::span<const Ball> balls;                    ///< more spheres, RayTarget::kBall with their index
};

/// cast_at() for each ray (each within `range`) into `hits`, then the push world's dynamic bodies (kMover) and the
/// balls (kBall) except ball `skip` (the caster's own). Equal distances keep the earlier kind in that order, and
/// the lower index within one. No allocation.
void cast_all(const WorldAtInstant& world, std::span<const Ray> rays, double range, int skip, std::span<RayHit> hits);

/// cast_all's last part: the push world's dynamic bodies, then the balls but `skip`, each only where strictly nearer
/// than what `hits` holds (the static solids' and the movers' answer). No allocation.
void cast_bodies_and_balls(const WorldAtInstant& world, std::span<const Ray> rays, int skip, std::span<RayHit> hits);

}  // namespace peg3d::sense
