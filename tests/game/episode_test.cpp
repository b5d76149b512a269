#include "game/episode.hpp"

#include <gtest/gtest.h>

#include "game/policy.hpp"
#include "geometry/motion_cone.hpp"
#include "test_arena.hpp"

namespace peg3d::game {
namespace {

using testing::make_arena;
using testing::scenario;

const Vec3 kSize(35, 35, 20);

GameConfig pursuit_config(const std::string& pursuer_policy, double evader_speed) {
  GameConfig c = preset("peg3d");
  c.pursuer.policy = pursuer_policy;
  c.evader.policy = "flee";
  c.evader.speed = evader_speed;
  return c;
}

TEST(Episode, PurePursuitCapturesAMotionlessEvaderInTheAnalyticTime) {
  // 20 m apart, the pursuer facing the evader: d(k) = 20 - 0.11 k <= 1 first at k = ceil(19 / 0.11) = 173.
  const auto s = scenario("line", {5, 17.5, 10}, {25, 17.5, 10});
  const auto arena = make_arena(kSize, {}, {s});
  const GameConfig c = pursuit_config("pure-pursuit", 0.0);
  Game game(arena, c);
  auto p = make_policy(c.pursuer, Role::kPursuer, 1);
  auto e = make_policy(c.evader, Role::kEvader, 2);
  const EpisodeResult r = game.play(s, *p, *e, false, 3);
  EXPECT_EQ(r.outcome, Outcome::kCapture);
  EXPECT_EQ(r.steps, 173);
  EXPECT_NEAR(r.duration, 17.3, 1e-9);
  EXPECT_NEAR(r.final_distance, 20.0 - 173 * 0.11, 1e-9);
  EXPECT_NEAR(r.pursuer_path, 173 * 0.11, 1e-9);
  EXPECT_EQ(r.evader_path, 0.0);
  EXPECT_EQ(r.collisions, 0);
}

TEST(Episode, CollisionEndsTheEpisodeAtTheTimeOfImpact) {
  // A sphere of radius 1 centred 10 m ahead: the pursuer's 0.25 m sphere touches it after 8.75 m, at 8.75 / 1.1 s.
  const auto s = scenario("wall", {5, 17.5, 10}, {30, 17.5, 10});
  const auto arena = make_arena(kSize, {{{15, 17.5, 10}, 1.0}}, {s});
  GameConfig c = pursuit_config("pure-pursuit", 0.0);
  c.pursuer.guard.enabled = false;
  Game game(arena, c);
  auto p = make_policy(c.pursuer, Role::kPursuer, 1);
  auto e = make_policy(c.evader, Role::kEvader, 2);
  const EpisodeResult r = game.play(s, *p, *e, false, 3);
  EXPECT_EQ(r.outcome, Outcome::kPursuerCollision);
  ASSERT_TRUE(r.first_collision.has_value());
  EXPECT_EQ(r.first_collision->agent, Role::kPursuer);
  EXPECT_EQ(r.first_collision->kind, world::ObstacleKind::kSphere);
  EXPECT_EQ(r.first_collision->obstacle_id, 0);
  EXPECT_NEAR(r.first_collision->time, 8.75 / 1.1, 2e-3);
  EXPECT_NEAR(r.first_collision->point.x(), 14.0, 2e-3);
  EXPECT_NEAR(r.pursuer_path, 8.75, 2e-3);
}

TEST(Episode, GuardSteersAroundTheObstacleWithoutCollision) {
  const auto s = scenario("wall", {5, 17.5, 10}, {30, 17.5, 10});
  const auto arena = make_arena(kSize, {{{15, 17.5, 10}, 1.0}}, {s});
  const GameConfig c = pursuit_config("pure-pursuit", 0.0);  // guard on by default
  Game game(arena, c);
  auto p = make_policy(c.pursuer, Role::kPursuer, 1);
  auto e = make_policy(c.evader, Role::kEvader, 2);
  const EpisodeResult r = game.play(s, *p, *e, false, 3);
  EXPECT_EQ(r.collisions, 0);
  EXPECT_EQ(r.outcome, Outcome::kCapture);
  EXPECT_GT(r.pursuer_path, 24.0);  // the detour is longer than the straight 24 m
}

TEST(Episode, PursuerHeadingStaysInTheApolloniusCone) {
  const auto s = scenario("open", {5, 17.5, 10}, {20, 17.5, 10});
  const auto arena = make_arena(kSize, {}, {s});
  GameConfig c = preset("peg3d");
  c.pursuer.policy = "random";  // the motion space has to do all the work
  c.evader.policy = "flee";
  Game game(arena, c);
  auto p = make_policy(c.pursuer, Role::kPursuer, 1);
  auto e = make_policy(c.evader, Role::kEvader, 2);
  std::vector<StepRecord> trace;
  game.play(s, *p, *e, false, 3, &trace);
  ASSERT_GT(trace.size(), 20u);
  const double half = pursuer_cone_half_angle(1.1, 1.0);
  for (std::size_t k = 1; k < trace.size(); ++k) {
    const Vec3 los = trace[k - 1].evader.position - trace[k - 1].pursuer.position;
    EXPECT_LE(angle_between(direction(trace[k].pursuer.heading), los), half + 1e-9) << "step " << k;
  }
}

TEST(Episode, EvaderMotionSpaceKeepsAlpha1AtLeastARightAngle) {
  const auto s = scenario("open", {5, 17.5, 10}, {20, 17.5, 10});
  const auto arena = make_arena(kSize, {}, {s});
  GameConfig c = preset("paper");  // the paper turns the evader's motion space on
  c.evader.steering.polar_margin = kPi / 3;  // away from the poles every heading change is within reach
  c.pursuer.policy = "pure-pursuit";
  c.evader.policy = "random";
  Game game(arena, c);
  auto p = make_policy(c.pursuer, Role::kPursuer, 1);
  auto e = make_policy(c.evader, Role::kEvader, 2);
  std::vector<StepRecord> trace;
  game.play(s, *p, *e, false, 3, &trace);
  for (std::size_t k = 1; k < trace.size(); ++k) {
    const Vec3 ep = trace[k - 1].pursuer.position - trace[k - 1].evader.position;
    EXPECT_GE(angle_between(direction(trace[k].evader.heading), ep), kPi / 2 - 1e-9) << "step " << k;
  }
}

TEST(Episode, SameSeedSameEpisodeDifferentSeedDifferentEpisode) {
  const auto s = scenario("open", {5, 5, 3}, {20, 25, 8});
  const auto arena = make_arena(kSize, {{{12, 15, 5}, 1.0}}, {s});
  const GameConfig c = preset("peg3d");
  auto run = [&](std::uint64_t seed) {
    Game game(arena, c);
    auto p = make_policy(c.pursuer, Role::kPursuer, seed);
    auto e = make_policy(c.evader, Role::kEvader, seed + 1);
    EpisodeResult last;
    for (int i = 0; i < 5; ++i) last = game.play(s, *p, *e, true, seed + 2 + i);
    return last;
  };
  const EpisodeResult a = run(10), b = run(10), d = run(11);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.pursuer_path, b.pursuer_path);
  EXPECT_EQ(a.pursuer_return, b.pursuer_return);
  EXPECT_EQ(a.evader_return, b.evader_return);
  EXPECT_NE(a.pursuer_return, d.pursuer_return);
}

TEST(Episode, StartInsideAnObstacleIsRejected) {
  const auto s = scenario("bad", {15, 17.5, 10}, {30, 17.5, 10});
  const auto arena = make_arena(kSize, {{{15.5, 17.5, 10}, 1.0}}, {scenario("ok", {5, 5, 5}, {30, 30, 5})});
  Game game(arena, preset("peg3d"));
  EXPECT_THROW(game.start(s, 0), std::runtime_error);
}

}  // namespace
}  // namespace peg3d::game
