#include "sense/world_rays.hpp"

namespace peg3d::sense {

RayHit cast_at(const StaticRayScene& scene, const world::MoverTimeline* movers, double t, const Ray& ray, double range) {
  const RayHit fixed = scene.cast(ray, range);
  if (movers == nullptr || movers->count() == 0) return fixed;
  // Movers only nearer than the static hit matter: the static distance bounds their search.
  const world::MoverHit moving = movers->first_along(ray, t, fixed.distance);
  if (moving.mover < 0 || moving.distance >= fixed.distance) return fixed;
  return {moving.distance, RayTarget::kMover, moving.mover};
}

}  // namespace peg3d::sense
