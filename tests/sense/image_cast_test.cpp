// An image's rays (sense/image_cast.hpp) meet what sense::cast_all meets: on forest's trunks, quarry's terrain and
// 640 movers at their instant, a field of spheres and cylinders that crowd and straddle the eye, and with agents'
// balls, every pixel's target, index and distance (exact in double) are cast_all's, over many eyes, headings,
// sizes, fields of view, mounts and ranges.
#include "sense/image_cast.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <random>

#include "core/random.hpp"
#include "sense/depth_camera.hpp"
#include "world/map/map_loader.hpp"

namespace peg3d::sense {
namespace {

std::shared_ptr<const world::Arena> arena_of(const std::string& map) {
  static std::map<std::string, std::shared_ptr<const world::Arena>> built;
  auto& a = built[map];
  if (!a) a = world::Arena::build(world::load_map(std::filesystem::path(PEG3D_SOURCE_DIR) / map));
  return a;
}

// The paper's arena holding 300 random spheres and cylinders of up to 3 m: many in view, some around the eye.
std::shared_ptr<const world::Arena> crowded() {
  static std::shared_ptr<const world::Arena> a;
  if (a) return a;
  world::MapSpec m = world::load_map(std::filesystem::path(PEG3D_SOURCE_DIR) / "maps/paper.yaml");
  Rng rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3 lo = m.bounds.lo, size = m.bounds.size();
  for (int i = 0; i < 150; ++i) {
    m.spheres.push_back({lo + size.cwiseProduct(Vec3(u(rng), u(rng), u(rng))), 0.2 + 2.8 * u(rng)});
    m.cylinders.push_back({lo + size.cwiseProduct(Vec3(u(rng), u(rng), 0.0)), 0.1 + 1.5 * u(rng), 1.0 + 18.0 * u(rng)});
  }
  m.scenarios.clear();
  m.resolution = 0.5;
  return a = world::Arena::build(m);
}

struct Tally {
  long pixels = 0, met = 0, differ = 0;
  std::map<RayTarget, long> targets;
};

// Images from random eyes and headings (a mount and a size drawn too); each pixel against cast_all.
void expect_images_match(const world::Arena& arena, const world::MoverTimeline* movers, int images, std::uint64_t seed,
                         Tally& tally, bool balls = false) {
  const StaticRayScene scene(arena);
  Rng rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box inner = arena.bounds().shrunk(0.3);
  ImageCastScratch scratch;
  for (int q = 0; q < images; ++q) {
    DepthCameraConfig c;
    c.width = 8 + int(56 * u(rng)), c.height = 4 + int(44 * u(rng));
    c.hfov = 20.0 + 140.0 * u(rng);
    c.range = 3.0 + 30.0 * u(rng);
    c.mount_azimuth = u(rng) < 0.3 ? 360.0 * (u(rng) - 0.5) : 0.0;
    c.mount_elevation = u(rng) < 0.3 ? 180.0 * (u(rng) - 0.5) : 0.0;
    const DepthCamera camera(c);
    const Vec3 eye = inner.lo + inner.size().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    const Heading h{2 * kPi * u(rng), 0.2 + (kPi - 0.4) * u(rng)};
    std::vector<Ray> rays(std::size_t(camera.pixels()));
    camera.rays_at(eye, h, rays);
    WorldAtInstant w;
    w.scene = &scene, w.movers = movers, w.time = movers != nullptr ? 30.0 * u(rng) : 0.0;
    std::vector<Ball> agents;
    if (balls) {  // the eye's own ball (skipped), and others about it
      agents.push_back({eye, 0.25});
      for (int b = 0; b < 4; ++b) agents.push_back({eye + 6.0 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5), 0.3 + u(rng)});
      w.balls = agents;
    }
    std::vector<RayHit> got(rays.size()), want(rays.size());
    // Odd images without their pinhole: the tiles' path.
    const Pinhole pinhole = camera.pinhole_at(h);
    cast_image(w, rays, c.width, q % 2 == 0 ? &pinhole : nullptr, c.range, balls ? 0 : -1, got, scratch);
    cast_all(w, rays, c.range, balls ? 0 : -1, want);
    for (std::size_t k = 0; k < rays.size(); ++k) {
      ++tally.pixels;
      tally.met += want[k].target != RayTarget::kNone;
      ++tally.targets[want[k].target];
      const bool same = got[k].target == want[k].target && got[k].index == want[k].index &&
                        std::abs(got[k].distance - want[k].distance) <= 1e-12 * (1.0 + want[k].distance);
      if (!same) {
        ++tally.differ;
        // A difference is a tie in float between two solids at one distance, never a solid missed.
        ASSERT_NEAR(got[k].distance, want[k].distance, 1e-5) << "image " << q << " pixel " << k;
      }
    }
  }
}

TEST(ImageCast, OnForestEveryPixelMeetsWhatCastAllMeets) {
  Tally t;
  expect_images_match(*arena_of("maps/forest.yaml"), nullptr, 300, 1, t);
  std::printf("forest: %ld pixels, %ld met, %ld differ\n", t.pixels, t.met, t.differ);
  EXPECT_EQ(t.differ, 0);
  EXPECT_GT(t.targets[RayTarget::kCylinder], t.pixels / 20);
  EXPECT_GT(t.targets[RayTarget::kArenaFace], t.pixels / 20);
}

TEST(ImageCast, OnQuarryTheTerrainAndTheMoversAtTheirInstantAreMet) {
  const auto arena = arena_of("maps/quarry.yaml");
  const auto movers = arena->movers_until(31.0);
  Tally t;
  expect_images_match(*arena, movers.get(), 200, 2, t);
  std::printf("quarry: %ld pixels, %ld met, %ld differ, %ld on movers\n", t.pixels, t.met, t.differ,
              t.targets[RayTarget::kMover]);
  EXPECT_LE(t.differ, t.pixels / 100000);  // ties in float between a triangle and another solid, if any
  EXPECT_GT(t.targets[RayTarget::kTriangle], t.pixels / 10);
  EXPECT_GT(t.targets[RayTarget::kMover], 100);
}

TEST(ImageCast, ACrowdOfSpheresAndCylindersAroundTheEyeAndTheAgentsBallsAreMet) {
  Tally t;
  expect_images_match(*crowded(), nullptr, 300, 3, t, /*balls=*/true);
  std::printf("crowded: %ld pixels, %ld met, %ld differ\n", t.pixels, t.met, t.differ);
  EXPECT_EQ(t.differ, 0);
  EXPECT_GT(t.targets[RayTarget::kSphere], t.pixels / 20);
  EXPECT_GT(t.targets[RayTarget::kCylinder], t.pixels / 20);
  EXPECT_GT(t.targets[RayTarget::kBall], 100);
}

}  // namespace
}  // namespace peg3d::sense
