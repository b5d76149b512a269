#include "sense/world_rays.hpp"

namespace peg3d::sense {

RayHit cast_at(const StaticRayScene& scene, const world::MoverTimeline* movers, double t, const Ray& ray, double range) {
  WorldAtInstant w;
  w.scene = &scene;
  w.movers = movers;
  w.time = t;
  RayHit hit;
  cast_all(w, {&ray, 1}, range, -1, {&hit, 1});
  return hit;
}

void cast_all(const WorldAtInstant& w, std::span<const Ray> rays, double range, int skip, std::span<RayHit> hits) {
  w.scene->cast(rays, range, hits);
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const Ray& ray = rays[k];
    RayHit& hit = hits[k];
    if (w.movers != nullptr && w.movers->count() > 0) {
      // Movers only nearer than the static hit matter: the static distance bounds their search.
      const world::MoverHit moving = w.movers->first_along(ray, w.time, hit.distance);
      if (moving.mover >= 0 && moving.distance < hit.distance) hit = {moving.distance, RayTarget::kMover, moving.mover};
    }
    if (w.push != nullptr) {
      // Push mode's bodies move with the run: no index over them; each body's bounding ball is tried first.
      for (int m = 0; m < w.push->movers(); ++m) {
        const world::MoverSpec& spec = w.map->movers[std::size_t(m)];
        if (spec.kinematic()) continue;  // on the timeline
        const Pose pose = w.push->pose(m);
        if (!ray_sphere(ray, pose.position, spec.shape.bounding_radius(), hit.distance)) continue;
        const auto d = ray_shape(ray, spec.shape, pose, hit.distance);
        if (d && *d < hit.distance) hit = {*d, RayTarget::kMover, m};
      }
    }
    for (std::size_t b = 0; b < w.balls.size(); ++b) {
      const Ball& ball = w.balls[b];
      if (static_cast<int>(b) == skip || ball.radius <= 0.0) continue;
      const auto d = ray_sphere(ray, ball.centre, ball.radius, hit.distance);
      if (d && *d < hit.distance) hit = {*d, RayTarget::kBall, static_cast<int>(b)};
    }
  }
}

}  // namespace peg3d::sense
