#pragma once
// What a ray meets in the world at an instant: the static scene's solids and the movers where they are then
// (scripted movers exactly, dynamic bodies as the timeline stores them).

#include "sense/static_ray_scene.hpp"
#include "world/bodies/mover_timeline.hpp"

namespace peg3d::sense {

/// The first solid along the ray within `range` at time t (s): the static scene's or a mover's (`movers` null:
/// a map without movers). A static solid and a mover met at one distance: the static one.
RayHit cast_at(const StaticRayScene& scene, const world::MoverTimeline* movers, double t, const Ray& ray, double range);

}  // namespace peg3d::sense
