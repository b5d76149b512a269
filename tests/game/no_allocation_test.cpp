// The step loop allocates nothing: whole training and evaluation episodes (observe, act, steer, move, sweep,
// capture, reward, learn, record) run without a single operator new once the Sim, its state and the
// policies exist, for one against one and for teams. This test program replaces the global operator new
// with a counting one, so it is a target of its own. Own maps are the exception: they grow with what their agents
// saw, and count their own allocations.

#include <gtest/gtest.h>

#include <LinearMath/btAlignedAllocator.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

#include "../support/counting_new.hpp"
#include "core/random.hpp"
#include "game/episode.hpp"
#include "players/lineup.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::game {
namespace {

using namespace peg3d::players;

void expect_no_allocation(const char* map, const char* preset_name, AgentCollisions collisions, bool lidar = false,
                          bool own_map = false, bool sight = false) {
  const auto arena = world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/" + map));
  GameConfig c = preset(preset_name);
  c.team.agent_collisions = collisions;
  if (lidar) {
    // 64 rays in 4 rows, with noise and dropouts; the pursuer every step, the evader every other step.
    for (AgentConfig* a : {&c.pursuer, &c.evader}) {
      a->sensors.lidar.azimuth_rays = 16;
      a->sensors.lidar.elevation_rays = 4;
      a->sensors.lidar.elevation_fov = 60.0;
      a->sensors.lidar.noise = 0.02;
      a->sensors.lidar.dropout = 0.1;
    }
    c.evader.sensors.lidar.period = 2;
    if (own_map) {
      for (AgentConfig* a : {&c.pursuer, &c.evader}) a->map.enabled = true, a->observation.obstacles = ObstacleSource::kOwnMap;
    }
  }
  if (sight) {
    // Limited sight, in a cone ahead, dead-reckoned and shared by the pursuers.
    for (AgentConfig* a : {&c.pursuer, &c.evader}) a->sensors.sight.enabled = true, a->sensors.sight.fov = 240.0;
    c.pursuer.sensors.sight.estimate = sense::SightEstimate::kDeadReckoning;
    c.pursuer.sensors.sight.share = true;
  }
  const Sim sim(arena, c);
  SimState state(sim);
  const auto& scenarios = arena->map().scenarios;
  // One lineup per scenario (team sizes differ between scenarios).
  std::vector<Lineup> lineups(scenarios.size());
  for (std::size_t k = 0; k < scenarios.size(); ++k) {
    add_configured(lineups[k], c, Role::kPursuer, static_cast<int>(scenarios[k].pursuers.size()), 1 + k);
    add_configured(lineups[k], c, Role::kEvader, static_cast<int>(scenarios[k].evaders.size()), 100 + k);
    play(sim, state, scenarios[k], lineups[k].policies(), true, 0);  // warm-up: anything lazily made is made now
  }
  Trace trace;
  trace.reserve(sim, scenarios[2], own_map ? 1 << 20 : 0);
  // An own map allocates when its scans reach more bricks than it has held (sense/scan_map.hpp) and counts those
  // allocations: every other one is the step loop's.
  const auto map_allocations = [&] {
    long n = 0;
    for (const auto& m : state.sensing.maps) n += m ? long(m->allocations()) : 0;
    return n;
  };
  const long before = testing::g_allocations.load(), maps_before = map_allocations();
  long steps = 0;
  for (std::uint64_t k = 0; k < 8; ++k) {
    const std::size_t i = k % scenarios.size();
    steps += play(sim, state, scenarios[i], lineups[i].policies(), true, derive_seed(3, {k})).steps;
  }
  steps += play(sim, state, scenarios[1], lineups[1].policies(), false, 4).steps;
  steps += play(sim, state, scenarios[2], lineups[2].policies(), false, 5, &trace).steps;
  const long maps_grew = map_allocations() - maps_before;
  EXPECT_EQ(testing::g_allocations.load() - before - maps_grew, 0) << map << " " << preset_name << ": allocations over " << steps << " steps";
  EXPECT_LE(maps_grew, 40) << "the maps grow by doubling";
  EXPECT_GT(steps, 1000) << map << " " << preset_name;
}

TEST(GameNoAllocation, OneAgainstOneTrainingAndEvaluation) {
  for (const char* name : kPresetNames) expect_no_allocation("maps/paper.yaml", name, AgentCollisions::kNone);
}

TEST(GameNoAllocation, ForestTrainingAndEvaluation) {
  // Among the trunks the guard's last resort queries Bullet for the obstacles near an agent on many steps.
  expect_no_allocation("maps/forest.yaml", "peg3d", AgentCollisions::kNone);
}

TEST(GameNoAllocation, MovingObstacleMapsTrainingAndEvaluation) {
  expect_no_allocation("maps/patrol.yaml", "peg3d", AgentCollisions::kNone);
  expect_no_allocation("maps/rockfall.yaml", "peg3d", AgentCollisions::kNone);
}

TEST(GameNoAllocation, LidarScans) {
  expect_no_allocation("maps/forest.yaml", "peg3d", AgentCollisions::kNone, true);
  expect_no_allocation("maps/patrol.yaml", "peg3d", AgentCollisions::kNone, true);
  expect_no_allocation("maps/pack.yaml", "peg3d", AgentCollisions::kAll, true);
}

TEST(GameNoAllocation, OwnMaps) {
  expect_no_allocation("maps/forest.yaml", "peg3d", AgentCollisions::kNone, true, true);
  expect_no_allocation("maps/pack.yaml", "peg3d", AgentCollisions::kNone, true, true);
}

TEST(GameNoAllocation, LimitedSight) {
  expect_no_allocation("maps/forest.yaml", "peg3d", AgentCollisions::kNone, false, false, true);
  expect_no_allocation("maps/pack.yaml", "peg3d", AgentCollisions::kNone, false, false, true);
  expect_no_allocation("maps/patrol.yaml", "peg3d", AgentCollisions::kNone, false, false, true);
}

TEST(GameNoAllocation, TeamsTrainingAndEvaluation) {
  expect_no_allocation("maps/pack.yaml", "peg3d", AgentCollisions::kNone);
  expect_no_allocation("maps/pack.yaml", "peg3d", AgentCollisions::kAll);
}

}  // namespace
}  // namespace peg3d::game

namespace peg3d::game {
namespace {

std::atomic<long> g_bullet_allocations{0};
void* counting_bullet_alloc(std::size_t n) {
  ++g_bullet_allocations;
  return std::malloc(n);
}
void bullet_free(void* p) { std::free(p); }

// Push mode: reset() builds the run's Bullet world (allocating); once warm, every step() after it makes no
// allocation of its own (events, touches and scratch are sized by reset). Bullet's allocator is counted apart: its pair cache
// and contact pools grow as new pairs appear in a fresh world, so it may allocate during the first contacts.
TEST(GameNoAllocation, PushModeSteps) {
  const auto arena =
      world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/tests/collision/maps/push.yaml"));
  GameConfig c = preset("peg3d");
  c.mover_dynamics = MoverDynamics::kPush;
  c.collision = CollisionMode::kPenalize;
  c.time_limit = 10.0;
  c.evader.speed = 0.0;
  c.pursuer.guard.enabled = c.evader.guard.enabled = false;  // drive straight into the bodies
  c.pursuer.motion_space = false;
  const Sim sim(arena, c);
  SimState st(sim);
  btAlignedAllocSetCustom(counting_bullet_alloc, bullet_free);
  long steps = 0, pushes = 0, collisions = 0, bullet = 0;
  const std::array<Steering, 2> straight{};
  // Warm-up: the shared timeline's blocks (here the scripted movers', none) are built on the first queries.
  reset(sim, st, *arena->map().find_scenario("ball-lane"), 7);
  while (!st.done) step(sim, st, straight);
  for (const char* scenario : {"ball-lane", "crate-lane", "solid-lane", "ball-lane"}) {
    reset(sim, st, *arena->map().find_scenario(scenario), 7);
    const long before = testing::g_allocations.load(), bullet_before = g_bullet_allocations.load();
    while (!st.done) {
      const StepEvents& e = step(sim, st, straight);
      pushes += static_cast<long>(e.pushes.size());
      collisions += static_cast<long>(e.collisions.size());
      ++steps;
    }
    bullet += g_bullet_allocations.load() - bullet_before;
    EXPECT_EQ(testing::g_allocations.load() - before, 0) << scenario << ": operator new in step()";
  }
  btAlignedAllocSetCustom(std::malloc, std::free);
  EXPECT_GT(pushes, 0);
  EXPECT_GT(collisions, 0);
  std::printf("push mode: %ld steps, %ld pushes, %ld collisions; Bullet allocated %ld times during them\n", steps, pushes,
              collisions, bullet);
}

}  // namespace
}  // namespace peg3d::game
