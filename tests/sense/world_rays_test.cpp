// Rays against the world at an instant (sense/world_rays.hpp): on valley's terrain with scripted movers of every
// shape and falling bodies, every ray meets what testing every static solid and every mover meets, at its
// distance.
#include "sense/world_rays.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "core/random.hpp"
#include "world/map/map_loader.hpp"

namespace peg3d::sense {
namespace {

TEST(WorldRays, EveryRayMeetsWhatTestingEverySolidAndMoverMeets) {
  Rng rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  world::MapSpec m = world::load_map(std::filesystem::path(PEG3D_SOURCE_DIR) / "maps/valley.yaml");
  m.resolution = 0.5;
  m.scenarios.clear();
  Shape shapes[3];
  shapes[0].kind = Shape::Kind::kSphere, shapes[0].radius = 0.8;
  shapes[1].kind = Shape::Kind::kCylinder, shapes[1].radius = 0.5, shapes[1].height = 2.0;
  shapes[2].kind = Shape::Kind::kBox, shapes[2].size = Vec3(1.5, 0.6, 1.0);
  const Vec3 lo = m.bounds.lo, size = m.bounds.size();
  for (int k = 0; k < 60; ++k) {
    world::MoverSpec s;
    s.shape = shapes[k % 3];
    if (k % 2 == 0) {
      s.motion = world::MoverSpec::Motion::kOrbit;
      s.orbit = {lo + size.cwiseProduct(Vec3(0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng), 0.5 + 0.4 * u(rng))), 1 + 4 * u(rng),
                 5 + 20 * u(rng), Vec3::UnitZ(), 6 * u(rng)};
    } else if (k % 3 != 0) {
      const Vec3 a = lo + size.cwiseProduct(Vec3(0.1, 0.1 + 0.8 * u(rng), 0.4 + 0.4 * u(rng)));
      s.motion = world::MoverSpec::Motion::kPath;
      s.path = {{a, a + Vec3(0.8 * size.x(), 0, 0)}, 0.5 + 3 * u(rng), false};
    } else {
      s.motion = world::MoverSpec::Motion::kDynamic;
      s.start = lo + size.cwiseProduct(Vec3(0.1 + 0.8 * u(rng), 0.1 + 0.8 * u(rng), 0.8));
    }
    m.movers.push_back(s);
  }
  const auto arena = world::Arena::build(m);
  const auto movers = arena->movers_until(15.0);
  const StaticRayScene scene(*arena);
  int on_movers = 0;
  for (int q = 0; q < 3000; ++q) {
    const double time = 14.9 * u(rng), range = 2.0 + 40.0 * u(rng);
    const Ray ray{lo + size.cwiseProduct(Vec3(u(rng), u(rng), u(rng))), Vec3(n(rng), n(rng), n(rng)).normalized()};
    const RayHit got = cast_at(scene, movers.get(), time, ray, range);
    RayHit want = cast_every_solid(*arena, ray, range);
    const world::MoverHit moving = movers->first_along_scan(ray, time, want.distance);
    if (moving.mover >= 0 && moving.distance < want.distance) want = {moving.distance, RayTarget::kMover, moving.mover};
    ASSERT_EQ(got.target, want.target) << "ray " << q;
    ASSERT_EQ(got.index, want.index) << "ray " << q;
    ASSERT_NEAR(got.distance, want.distance, 1e-9) << "ray " << q;
    on_movers += got.target == RayTarget::kMover;
  }
  std::printf("%d of 3000 rays met a mover first\n", on_movers);
  EXPECT_GT(on_movers, 100);
}

}  // namespace
}  // namespace peg3d::sense
