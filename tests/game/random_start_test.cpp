// Random starts (game/random_start.hpp): where they put the agents, and when they give up.
#include <gtest/gtest.h>

#include <cmath>

#include "core/random.hpp"
#include "game/random_start.hpp"
#include "test_arena.hpp"

namespace peg3d::game {
namespace {

constexpr double kRadius = 0.4;  // m, both agents (set below)

const std::vector<world::SphereObstacle>& spheres() {
  static const std::vector<world::SphereObstacle> s = {{{10, 10, 5}, 3.0}, {{4, 15, 3}, 1.5}};
  return s;
}

std::shared_ptr<const world::Arena> arena() {
  static const auto a = testing::make_arena(
      {20, 20, 10}, spheres(), {testing::team("T", {{2, 2, 5}, {2, 5, 5}}, {{17, 17, 5}, {17, 14, 5}, {14, 17, 5}})});
  return a;
}

GameConfig config() {
  GameConfig c = preset("peg3d");
  c.pursuer.radius = c.evader.radius = kRadius;
  return c;
}

TEST(RandomStart, PlacesEveryAgentInsideTheArenaClearOfObstaclesAndApart) {
  const Sim sim(arena(), config());
  const world::Scenario& like = arena()->map().scenarios[0];
  const Box box = arena()->bounds().shrunk(kRadius + kRandomStartClearance);
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const world::Scenario s = random_start(sim, like, seed, 8.0);
    ASSERT_EQ(s.name, like.name);
    ASSERT_EQ(s.pursuers.size(), 2u);
    ASSERT_EQ(s.evaders.size(), 3u);
    ASSERT_NE(s.pursuers[0].position, like.pursuers[0].position) << "fell back at seed " << seed;
    std::vector<Vec3> all;
    for (const auto* role : {&s.pursuers, &s.evaders}) {
      for (const auto& a : *role) {
        all.push_back(a.position);
        EXPECT_FALSE(a.heading);
      }
    }
    for (std::size_t i = 0; i < all.size(); ++i) {
      EXPECT_TRUE(box.contains(all[i])) << seed;
      // The arena's distance is voxel-accurate, so the exact clearance may be short by a voxel's diagonal.
      for (const auto& o : spheres())
        EXPECT_GE((all[i] - o.center).norm() - o.radius, kRadius + kRandomStartClearance - 0.25 * std::sqrt(3.0)) << seed;
      for (std::size_t j = 0; j < i; ++j) {
        const bool same_role = (i < 2) == (j < 2);
        if (same_role) {
          EXPECT_GE((all[i] - all[j]).norm(), 2 * kRadius + kRandomStartClearance) << seed;
        } else {
          EXPECT_GT((all[i] - all[j]).norm(), 8.0) << seed;
        }
      }
    }
  }
}

TEST(RandomStart, DrawsPlacesOverTheWholeArena) {
  // Uniform over the free box: the mean of many draws lies near the box's centre (the spheres shift it a
  // little), and draws reach every octant.
  const Sim sim(arena(), config());
  const world::Scenario& like = arena()->map().scenarios[0];
  Vec3 sum = Vec3::Zero();
  int octants[8] = {};
  const int n = 2000;
  for (int k = 0; k < n; ++k) {
    const Vec3 p = random_start(sim, like, derive_seed(5, {std::uint64_t(k)}), 0.0).evaders[2].position;
    sum += p;
    ++octants[(p.x() > 10) + 2 * (p.y() > 10) + 4 * (p.z() > 5)];
  }
  EXPECT_NEAR(sum.x() / n, 10.0, 0.6);
  EXPECT_NEAR(sum.y() / n, 10.0, 0.6);
  EXPECT_NEAR(sum.z() / n, 5.0, 0.4);
  for (const int c : octants) EXPECT_GT(c, n / 16);
}

TEST(RandomStart, IsAFunctionOfItsSeed) {
  const Sim sim(arena(), config());
  const world::Scenario& like = arena()->map().scenarios[0];
  const world::Scenario a = random_start(sim, like, 42, 8.0), b = random_start(sim, like, 42, 8.0),
                        c = random_start(sim, like, 43, 8.0);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(a.evaders[i].position, b.evaders[i].position);
  EXPECT_NE(a.evaders[0].position, c.evaders[0].position);
}

TEST(RandomStart, KeepsTheScenarioWhenNoPlaceFits) {
  // No two points of a 20 x 20 x 10 box lie 40 m apart.
  const Sim sim(arena(), config());
  const world::Scenario& like = arena()->map().scenarios[0];
  const world::Scenario s = random_start(sim, like, 1, 40.0);
  EXPECT_EQ(s.pursuers[0].position, like.pursuers[0].position);
  EXPECT_EQ(s.evaders[2].position, like.evaders[2].position);
}

TEST(RandomStart, NeverStartsWithinCaptureDistance) {
  // A gap of 0 still keeps each pursuer beyond capture distance of each evader.
  GameConfig c = config();
  c.capture_distance = 6.0;
  const Sim sim(arena(), c);
  const world::Scenario& like = arena()->map().scenarios[0];
  for (std::uint64_t seed = 0; seed < 100; ++seed) {
    const world::Scenario s = random_start(sim, like, seed, 0.0);
    for (const auto& p : s.pursuers)
      for (const auto& e : s.evaders) EXPECT_GT((p.position - e.position).norm(), 6.0) << seed;
  }
}

}  // namespace
}  // namespace peg3d::game
