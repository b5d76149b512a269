// Push mode in the game (mover_dynamics = push, world/bodies/push_world.hpp): pushes are events, not collisions; a
// solid body is a collision; the agents' sensing sees the bodies where the run moved them; runs of a seed are
// the same in any thread; the default mode on the same map is unchanged by the setting's existence.
#include <gtest/gtest.h>

#include <thread>

#include "core/hash.hpp"
#include "game/episode.hpp"
#include "players/lineup.hpp"
#include "world/map/map_loader.hpp"

namespace peg3d::game {
namespace {

std::shared_ptr<const world::Arena> push_arena() {
  static const auto arena =
      world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/tests/collision/maps/push.yaml"));
  return arena;
}

GameConfig straight(MoverDynamics mode) {
  GameConfig c = preset("peg3d");
  c.mover_dynamics = mode;
  c.collision = CollisionMode::kPenalize;
  c.pursuer.guard.enabled = c.evader.guard.enabled = false;
  c.pursuer.motion_space = false;
  c.evader.speed = 0.0;
  c.time_limit = 8.0;
  return c;
}

// Drives the pursuer straight along +x for the whole episode; returns the trace.
Trace drive(const Sim& sim, const char* scenario) {
  SimState st(sim);
  reset(sim, st, *sim.arena().map().find_scenario(scenario), 1);
  Trace trace;
  trace.record(st, false);
  const std::array<Steering, 2> none{};
  while (!st.done) {
    step(sim, st, none);
    trace.record(st, true);
  }
  return trace;
}

TEST(PushMode, PushableBodiesArePushedNotCollidedWith) {
  const Sim sim(push_arena(), straight(MoverDynamics::kPush));
  ASSERT_TRUE(sim.pushes());
  const Trace t = drive(sim, "crate-lane");
  EXPECT_TRUE(t.collisions.empty());
  ASSERT_FALSE(t.pushes.empty());
  for (const PushEvent& p : t.pushes) EXPECT_EQ(p.obstacle_id, 1);
  // The pursuer was never stopped: it covered speed x time.
  const AgentFrame& last = t.at(t.frame_count() - 1, 0);
  EXPECT_NEAR(last.state.position.x(), 3.0 + 1.1 * 8.0, 1e-9);
}

TEST(PushMode, SolidBodiesAreCollisions) {
  const Sim sim(push_arena(), straight(MoverDynamics::kPush));
  const Trace t = drive(sim, "solid-lane");
  EXPECT_TRUE(t.pushes.empty());
  ASSERT_FALSE(t.collisions.empty());
  EXPECT_EQ(t.collisions.front().kind, world::ObstacleKind::kMover);
  EXPECT_EQ(t.collisions.front().obstacle_id, 2);
  // It stands in front of the crate's face (x = 7.5 less its radius), never inside.
  const AgentFrame& last = t.at(t.frame_count() - 1, 0);
  EXPECT_LE(last.state.position.x(), 7.5 - 0.25 + 1e-3);
  EXPECT_GT(last.state.position.x(), 7.5 - 0.25 - 0.05);
}

TEST(PushMode, SharedModeTreatsEveryBodyAsSolid) {
  const Sim sim(push_arena(), straight(MoverDynamics::kShared));
  EXPECT_FALSE(sim.pushes());
  const Trace t = drive(sim, "crate-lane");
  EXPECT_TRUE(t.pushes.empty());
  ASSERT_FALSE(t.collisions.empty());
  EXPECT_EQ(t.collisions.front().obstacle_id, 1);
}

TEST(PushMode, TheAgentSensesTheBodyWhereItWasPushed) {
  const Sim sim(push_arena(), straight(MoverDynamics::kPush));
  const Trace t = drive(sim, "crate-lane");
  // Pushed ahead of it, the crate stays within a few centimetres of the pursuer's sphere (r 0.25; the distance
  // is its centre's), about 4 m from where it started.
  const AgentFrame& last = t.at(t.frame_count() - 1, 0);
  EXPECT_GT(last.state.position.x(), 11.0);
  EXPECT_GT(last.percept.obstacle.distance, 0.25 - 1e-3);
  EXPECT_LT(last.percept.obstacle.distance, 0.35);
}

TEST(PushMode, SameSeedSameRunInAnyThread) {
  const Sim sim(push_arena(), straight(MoverDynamics::kPush));
  auto hash = [&](const Trace& t) {
    Fnv1a h;
    for (const AgentFrame& f : t.frames) {
      h.add_value(f.state.position.x());
      h.add_value(f.state.position.y());
      h.add_value(f.percept.obstacle.distance);
    }
    for (const PushEvent& p : t.pushes) h.add_value(p.point.x());
    return h.value();
  };
  const std::uint64_t here = hash(drive(sim, "ball-lane"));
  std::uint64_t a = 0, b = 0;
  std::thread ta([&] { a = hash(drive(sim, "ball-lane")); });
  std::thread tb([&] { b = hash(drive(sim, "ball-lane")); });
  ta.join();
  tb.join();
  EXPECT_EQ(a, here);
  EXPECT_EQ(b, here);
}

TEST(PushMode, PushNeedsExactSensing) {
  GameConfig c = straight(MoverDynamics::kPush);
  c.mover_sensing = MoverSensing::kOctree;
  EXPECT_THROW(Sim(push_arena(), c), InvalidParameter);
}

}  // namespace
}  // namespace peg3d::game
