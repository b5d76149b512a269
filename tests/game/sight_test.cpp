// Limited sight in the game (game/knowledge.hpp, SimState::sight, AgentConfig::sight): an opponent behind a pillar is
// known where it was last seen (or dead-reckoned), one in plain sight as it is; the field of view and the range
// bound what is seen; teammates that share see what any of them sees; rewards keep measuring the true distance;
// and on an open arena a game with sight on plays exactly as with full information.
#include <random>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "game/episode.hpp"
#include "game/knowledge.hpp"
#include "test_arena.hpp"

namespace peg3d::game {
namespace {

using testing::pillar_room;

// Agents that go where their command sends them: no motion space, no guard; headings along +x.
GameConfig straight(bool sight) {
  GameConfig c = preset("peg3d");
  c.initial_heading = InitialHeading::kPlusX;
  c.collision = CollisionMode::kPenalize;
  for (AgentConfig* a : {&c.pursuer, &c.evader}) {
    a->motion_space = false;
    a->guard.enabled = false;
    a->sensors.sight.enabled = sight;
  }
  return c;
}

void step_straight(const Sim& sim, SimState& st, int steps) {
  std::vector<Steering> none(std::size_t(st.agent_count()));
  for (int k = 0; k < steps; ++k) step(sim, st, none);
}

TEST(GameSight, AnOpponentBehindAPillarIsKnownWhereItWasLastSeen) {
  for (const double dt : {0.1, 0.05}) {
    GameConfig c = straight(true);
    c.dt = dt;
    const Sim sim(pillar_room(), c);
    SimState st(sim);
    // The evader starts right behind the pillar and flies on along +x, hidden all the way.
    reset(sim, st, testing::scenario("s", {4, 15, 5}, {20, 15, 5}), 1);
    EXPECT_FALSE(observe(st, 0).other_visible);
    EXPECT_EQ(observe(st, 0).other.position, Vec3(20, 15, 5));  // every agent knows the starts
    EXPECT_EQ(observe(st, 0).other_age, 0.0);
    step_straight(sim, st, 7);
    const AgentView& v = observe(st, 0);
    EXPECT_FALSE(v.other_visible);
    EXPECT_EQ(v.other.position, Vec3(20, 15, 5));
    EXPECT_DOUBLE_EQ(v.other_age, 7 * dt);
    // From itself to where it takes the evader to be.
    EXPECT_NEAR(v.percept.target_distance, 16.0 - 7 * dt * c.pursuer.speed, 1e-12);
    EXPECT_NE(st.agents[1].kinematics.position, Vec3(20, 15, 5));
  }
}

TEST(GameSight, DeadReckoningMovesTheLastSightingOnAtItsVelocityWithinTheArena) {
  GameConfig c = straight(true);
  c.pursuer.sensors.sight.estimate = sense::SightEstimate::kDeadReckoning;
  c.evader.speed = 0.7;
  const Sim sim(pillar_room(), c);
  SimState st(sim);
  reset(sim, st, testing::scenario("s", {4, 15, 5}, {20, 15, 5}), 1);
  for (const int steps : {3, 40, 200}) {
    step_straight(sim, st, steps - st.step);
    const AgentView& v = observe(st, 0);
    EXPECT_FALSE(v.other_visible);
    // At 0.7 m/s along +x, kept radius 0.25 inside the room's far wall at x = 30.
    EXPECT_NEAR(v.other.position.x(), std::min(20 + 0.7 * v.other_age, 30 - 0.25), 1e-9) << steps;
    EXPECT_NEAR(v.other.position.y(), 15, 1e-9);
    EXPECT_NEAR(v.other.position.z(), 5, 1e-9);
  }
}

TEST(GameSight, AnOpponentInPlainSightIsKnownAsItIs) {
  const Sim sim(pillar_room(), straight(true));
  SimState st(sim);
  reset(sim, st, testing::scenario("s", {4, 15, 5}, {20, 25, 5}), 1);
  step_straight(sim, st, 5);
  for (int i : {0, 1}) {
    const AgentView& v = observe(st, i);
    EXPECT_TRUE(v.other_visible);
    EXPECT_EQ(v.other_age, 0.0);
    EXPECT_EQ(v.other.position, st.agents[std::size_t(1 - i)].kinematics.position);
    EXPECT_EQ(v.other.heading.alpha, st.agents[std::size_t(1 - i)].kinematics.heading.alpha);
  }
}

TEST(GameSight, TheFieldOfViewAndTheRangeBoundWhatIsSeen) {
  // The pursuer heads +x; the evader is 10 m away, `bearing` deg to its left (level). No pillar.
  const auto arena = pillar_room(false);
  for (const double bearing : {30.0, 100.0, 135.0, 180.0}) {
    const Vec3 at = Vec3(15, 15, 5) + 10.0 * Vec3(std::cos(bearing * kPi / 180), std::sin(bearing * kPi / 180), 0);
    for (const double fov : {50.0, 70.0, 190.0, 210.0, 260.0, 280.0, 360.0}) {
      for (const double range : {9.9, 10.1}) {
        GameConfig c = straight(true);
        c.pursuer.sensors.sight.fov = fov;
        c.pursuer.sensors.sight.range = range;
        const Sim sim(arena, c);
        SimState st(sim);
        reset(sim, st, testing::scenario("s", {15, 15, 5}, at), 1);
        EXPECT_EQ(observe(st, 0).other_visible, bearing <= fov / 2 && range > 10.0)
            << bearing << " deg left, " << fov << " deg field, " << range << " m";
        EXPECT_TRUE(observe(st, 1).other_visible);  // the evader sees all round, far enough
      }
    }
  }
}

TEST(GameSight, TeammatesThatShareSeeWhatAnyOfThemSees) {
  // Pursuer 0 has the evader behind the pillar; pursuer 1 sees it from the side.
  for (const bool share : {false, true}) {
    GameConfig c = straight(true);
    c.pursuer.sensors.sight.share = share;
    const Sim sim(pillar_room(), c);
    SimState st(sim);
    reset(sim, st, testing::team("t", {{4, 15, 5}, {20, 27, 5}}, {{20, 15, 5}}), 1);
    step_straight(sim, st, 4);
    EXPECT_TRUE(observe(st, 1).other_visible);
    EXPECT_EQ(observe(st, 0).other_visible, share);
    EXPECT_EQ(observe(st, 0).other.position == st.agents[2].kinematics.position, share);
    EXPECT_EQ(observe(st, 0).other_age, share ? 0.0 : 4 * c.dt);
  }
}

TEST(GameSight, RewardsMeasureTheTrueDistance) {
  // The same moves with sight on and off: the percepts differ, the rewards do not.
  const Sim on(pillar_room(), straight(true)), off(pillar_room(), straight(false));
  SimState a(on), b(off);
  reset(on, a, testing::scenario("s", {4, 15, 5}, {20, 15, 5}), 1);
  reset(off, b, testing::scenario("s", {4, 15, 5}, {20, 15, 5}), 1);
  std::vector<Steering> none(2);
  for (int k = 0; k < 10; ++k) {
    const StepEvents& ea = step(on, a, none);
    const StepEvents& eb = step(off, b, none);
    for (int i : {0, 1}) {
      EXPECT_EQ(ea.agents[std::size_t(i)].reward.total, eb.agents[std::size_t(i)].reward.total) << "step " << k;
      EXPECT_EQ(a.agents[std::size_t(i)].kinematics.position, b.agents[std::size_t(i)].kinematics.position);
    }
  }
  EXPECT_NE(observe(a, 0).percept.target_distance, observe(b, 0).percept.target_distance);
}

TEST(GameSight, OnAnOpenArenaSightOnPlaysExactlyAsFullInformation) {
  // Nothing to hide behind and sight all round: every sighting is of now, so every input, move and reward is the
  // same, FACL agents learning and guidance laws alike.
  const auto arena = pillar_room(false);
  for (const std::string pursuer : {"facl", "apollonius"}) {
    std::vector<EpisodeResult> results;
    std::vector<Trace> traces(2);
    for (const bool sight : {false, true}) {
      GameConfig c = preset("peg3d");
      c.pursuer.policy = pursuer;
      c.time_limit = 20;
      c.pursuer.sensors.sight.enabled = c.evader.sensors.sight.enabled = sight;
      c.pursuer.sensors.sight.estimate = sense::SightEstimate::kDeadReckoning;
      const Sim sim(arena, c);
      results.push_back(testing::play_once(sim, testing::scenario("s", {3, 4, 5}, {20, 22, 6}), 9, &traces[sight]));
    }
    EXPECT_EQ(results[0].steps, results[1].steps);
    EXPECT_EQ(results[0].pursuer_return, results[1].pursuer_return);
    EXPECT_EQ(results[0].evader_return, results[1].evader_return);
    ASSERT_EQ(traces[0].frames.size(), traces[1].frames.size());
    for (std::size_t f = 0; f < traces[0].frames.size(); ++f) {
      const AgentFrame &x = traces[0].frames[f], &y = traces[1].frames[f];
      ASSERT_EQ(x.state.position, y.state.position) << "frame " << f;
      ASSERT_EQ(x.command.d_alpha, y.command.d_alpha) << "frame " << f;
      ASSERT_EQ(x.reward, y.reward) << "frame " << f;
      ASSERT_EQ(x.percept.target_distance, y.percept.target_distance) << "frame " << f;
    }
  }
}

}  // namespace
}  // namespace peg3d::game

namespace peg3d::game {
namespace {

TEST(GameSight, TheProbeKnowsWhatTheAgentsOwnMapHasSeen) {
  GameConfig c = straight(true);
  c.pursuer.sensors.lidar.azimuth_rays = 16;
  c.pursuer.sensors.lidar.range = 6.0;
  c.pursuer.map.enabled = true;
  const Sim sim(pillar_room(), c);
  SimState st(sim);
  reset(sim, st, testing::scenario("s", {4, 15, 5}, {20, 15, 5}), 1);
  const SightProbe* pursuer = observe(st, 0).probe;
  const SightProbe* evader = observe(st, 1).probe;
  ASSERT_NE(pursuer, nullptr);
  ASSERT_NE(evader, nullptr);
  EXPECT_TRUE(pursuer->mapped({4, 15, 5}));     // its own cell, which every ray crosses
  // 3 m out along its first ray left of the heading (16 rays over 360 degrees: at 11.25 degrees)
  EXPECT_TRUE(pursuer->mapped(Vec3(4, 15, 5) + 3.0 * Vec3(std::cos(kPi / 16), std::sin(kPi / 16), 0)));
  EXPECT_FALSE(pursuer->mapped({4, 15, 9}));    // above the level scan
  EXPECT_FALSE(pursuer->mapped({25, 15, 5}));   // beyond its range
  EXPECT_FALSE(evader->mapped({20, 15, 5}));    // no map
  EXPECT_TRUE(pursuer->clear({4, 15, 5}, {4, 25, 5}));
  EXPECT_FALSE(pursuer->clear({4, 15, 5}, {20, 15, 5}));  // through the pillar
}

TEST(GameSight, TheProbesClearanceIsTheDistanceToTheNearestSolidUpToTheFieldsCap) {
  // The pillar of radius 3 m at (15, 15): from points at random bearings, heights and distances, the probe's
  // clearance is the distance to its surface within the field's error (under one voxel diagonal, 0.43 m at 0.25 m;
  // docs/maps.md), and the cap (5 m) beyond.
  const Sim sim(pillar_room(), straight(true));
  SimState st(sim);
  reset(sim, st, testing::scenario("s", {4, 15, 5}, {26, 15, 5}), 1);
  const SightProbe* probe = observe(st, 0).probe;
  ASSERT_NE(probe, nullptr);
  std::mt19937_64 rng(56);
  std::uniform_real_distribution<double> bearing(-kPi, kPi), height(1.0, 9.0), out(0.3, 4.5);
  for (int k = 0; k < 100; ++k) {
    const double b = bearing(rng), d = out(rng);
    const Vec3 p(15 + (3 + d) * std::cos(b), 15 + (3 + d) * std::sin(b), height(rng));
    EXPECT_NEAR(probe->clearance(p), d, 0.25 * std::sqrt(3.0)) << p.transpose();
  }
  EXPECT_EQ(probe->clearance({27, 27, 5}), sim.arena().max_distance());  // 9 m from the pillar: the cap
  EXPECT_EQ(probe->clearance({15, 15, 5}), 0.0);                         // inside it
}

}  // namespace
}  // namespace peg3d::game
