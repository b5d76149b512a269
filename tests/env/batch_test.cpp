// The batch of games (env/batch.hpp): its buffers against each game's SimState, the ends of episodes where
// geometry puts them, next-step autoreset, agents played on the C++ side, and results that do not depend on
// the thread count.
#include "env/batch.hpp"
#include "players/registry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/hash.hpp"
#include "core/random.hpp"
#include "core/validation.hpp"
#include "game/episode.hpp"
#include "game/observation.hpp"
#include "players/saved_policy.hpp"
#include "support/numbers.hpp"
#include "support/unscripted.hpp"
#include "test_arena.hpp"

namespace peg3d::env {
namespace {

using game::Role;
using testing::team;

const Vec3 kSize(35, 35, 20);
const world::SphereObstacle kRock{{12, 20, 10}, 1.5};
constexpr int kLimitSteps = 100;  // time_limit 10 s at dt 0.1 s
using testing::kInf;
using testing::kNaN;

// Three 2 v 2 starts (agents 0, 1 pursuers; 2, 3 evaders) whose ends follow from geometry when the pursuers fly
// straight (zero commands from their chase headings, each facing its nearest evader) at standing evaders.
// Nobody's nearest opponent changes before the first end.
enum Start { kCapture, kCrash, kTimeout };
std::vector<world::Scenario> starts() {
  return {// P0 10 m from E0: captured when 10 - 0.11 k <= 1; P1 20 m from E1, 9 m short at the time limit.
          team("capture", {{5, 10, 10}, {5, 30, 10}}, {{15, 10, 10}, {25, 30, 10}}),
          // The rock lies between P0 and E0; the others are 25 m apart.
          team("crash", {{5, 20, 10}, {5, 2, 10}}, {{25, 20, 10}, {30, 2, 10}}),
          // Every evader over 32 m from every pursuer: only the time limit ends the game.
          team("timeout", {{3, 3, 3}, {32, 3, 3}}, {{3, 32, 17}, {32, 32, 17}})};
}

std::shared_ptr<const world::Arena> arena() {
  static const auto a = testing::make_arena(kSize, {kRock}, starts(), 0.5);
  return a;
}

// Pursuers at peg3d's 1.1 m/s without the obstacle guard (so P0 can hit the rock); standing evaders.
game::GameConfig standing_evaders() {
  game::GameConfig c = game::preset("peg3d");
  c.time_limit = 0.1 * kLimitSteps;
  c.pursuer.guard.enabled = false;
  c.evader.speed = 0.0;
  return c;
}
double pursuer_step() { return standing_evaders().pursuer.speed * standing_evaders().dt; }  // m per step

// The steps at which the first episode of each start ends, from the geometry above.
int capture_step() { return int(std::ceil((10.0 - standing_evaders().capture_distance) / pursuer_step())); }
int crash_step() {
  const double gap = kRock.center.x() - kRock.radius - standing_evaders().pursuer.radius - 5.0;  // m
  return int(std::ceil(gap / pursuer_step()));
}

BatchSettings settings(int games, int threads = 1, std::uint64_t seed = 11) {
  BatchSettings s;
  s.games = games;
  s.threads = threads;
  s.seed = seed;
  return s;
}

// Flat views of a batch's buffers.
struct Buffers {
  Batch& b;
  std::size_t at(int g, int i) const { return std::size_t(g) * std::size_t(b.agents()) + std::size_t(i); }
  float reward(int g, int i) const { return b.rewards()[at(g, i)]; }
  float term(int g, int i, int t) const { return b.reward_terms()[3 * at(g, i) + std::size_t(t)]; }
  bool terminated(int g, int i) const { return b.terminated()[at(g, i)] != 0; }
  bool truncated(int g, int i) const { return b.truncated()[at(g, i)] != 0; }
  bool acted(int g, int i) const { return b.acted()[at(g, i)] != 0; }
  bool active(int g, int i) const { return b.active()[at(g, i)] != 0; }
  bool collided(int g, int i) const { return b.collided()[at(g, i)] != 0; }
  bool captured(int g, int i) const { return b.captured()[at(g, i)] != 0; }
  bool reset(int g) const { return b.reset_flags()[std::size_t(g)] != 0; }
  std::vector<float> observation(int g, int i) const {
    const float* o = b.observations() + at(g, i) * std::size_t(b.observation_size());
    return {o, o + b.observation_size()};
  }
};

// What batch.hpp says agent i's observation is: its view's 20 entries, then up to k other opponents (its own
// opponent left out) and up to k teammates still in the game, nearest first, as (offset, 1), zeros after.
std::vector<float> expected_observation(const game::SimState& st, int i, int k) {
  std::vector<float> o(std::size_t(game::kObservationBase));
  game::observation_base(game::observe(st, i), o.data());
  const game::AgentState& me = st.agents[std::size_t(i)];
  for (const bool opponents : {true, false}) {
    std::vector<std::pair<double, Vec3>> near;
    for (int j = 0; j < st.agent_count(); ++j) {
      const game::AgentState& other = st.agents[std::size_t(j)];
      const bool opponent = other.role != me.role;
      if (j == i || !other.active || opponent != opponents || j == me.opponent) continue;
      const Vec3 d = other.kinematics.position - me.kinematics.position;
      near.emplace_back(d.norm(), d);
    }
    std::stable_sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (int n = 0; n < k; ++n) {
      const bool there = n < int(near.size());
      const Vec3 d = there ? near[std::size_t(n)].second : Vec3::Zero();
      o.insert(o.end(), {float(d.x()), float(d.y()), float(d.z()), there ? 1.0f : 0.0f});
    }
  }
  return o;
}

std::vector<Vec3> positions(const game::SimState& st) {
  std::vector<Vec3> p;
  for (const game::AgentState& a : st.agents) p.push_back(a.kinematics.position);
  return p;
}
std::vector<Vec3> start_positions(const world::Scenario& s) {
  std::vector<Vec3> p;
  for (int i = 0; i < s.agents(); ++i) p.push_back(s.start(i).position);
  return p;
}

// The CommandError a step of `actions` raises (a test failure, and an error naming nothing, when it steps).
game::CommandError refusal(Batch& batch, const std::vector<double>& actions) {
  try {
    batch.step(actions.data());
  } catch (const game::CommandError& e) {
    return e;
  }
  ADD_FAILURE() << "the step was taken";
  return game::CommandError(0, -1, "", "");
}

// The buffers of a game the last step (or reset) started afresh: nothing happened to anyone, everyone is in.
void expect_fresh(const Batch& batch, Buffers& buf, int g) {
  EXPECT_TRUE(buf.reset(g));
  for (int i = 0; i < batch.agents(); ++i) {
    SCOPED_TRACE(::testing::Message() << "game " << g << ", agent " << i);
    EXPECT_EQ(buf.reward(g, i), 0.0f);
    for (int t = 0; t < 3; ++t) EXPECT_EQ(buf.term(g, i, t), 0.0f);
    EXPECT_FALSE(buf.terminated(g, i));
    EXPECT_FALSE(buf.truncated(g, i));
    EXPECT_FALSE(buf.acted(g, i));
    EXPECT_FALSE(buf.collided(g, i));
    EXPECT_FALSE(buf.captured(g, i));
    EXPECT_TRUE(buf.active(g, i));
    EXPECT_EQ(buf.observation(g, i), expected_observation(batch.state(g), i, 2));
  }
}

TEST(EnvBatch, ResetFillsEveryBufferFromEachGamesStart) {
  Batch batch(arena(), standing_evaders(), settings(3, 2));
  Buffers buf{batch};
  ASSERT_EQ(batch.agents(), 4);
  EXPECT_EQ(batch.pursuers(), 2);
  EXPECT_EQ(batch.observation_size(), game::kObservationBase + 2 * 2 * 4);
  EXPECT_EQ(batch.agent_names(), (std::vector<std::string>{"pursuer_0", "pursuer_1", "evader_0", "evader_1"}));
  for (int g = 0; g < 3; ++g) {
    EXPECT_EQ(batch.state(g).step, 0);
    expect_fresh(batch, buf, g);
  }
}

TEST(EnvBatch, NeighbourSlotsHoldTheNearestOtherAgentsFirstThenZeros) {
  // P0 plays E0 (15 m; E2 19 m, E1 22 m away); its teammates are P2 (3 m) and P1 (10 m): nearest first is not
  // index order.
  const auto three = testing::make_arena(
      kSize, {}, {team("3v3", {{5, 5, 5}, {5, 15, 5}, {8, 5, 5}}, {{20, 5, 5}, {5, 27, 5}, {24, 5, 5}})}, 0.5);
  for (const int k : {1, 3}) {
    SCOPED_TRACE(::testing::Message() << k << " neighbours");
    BatchSettings s = settings(1);
    s.neighbours = k;
    Batch batch(three, standing_evaders(), s);
    ASSERT_EQ(batch.observation_size(), game::kObservationBase + 2 * k * 4);
    ASSERT_EQ(batch.state(0).agents[0].opponent, 3);
    const std::vector<float> o = Buffers{batch}.observation(0, 0);
    const std::vector<float> opponents(o.begin() + game::kObservationBase, o.begin() + game::kObservationBase + 4 * k);
    const std::vector<float> teammates(o.begin() + game::kObservationBase + 4 * k, o.end());
    if (k == 1) {
      EXPECT_EQ(opponents, (std::vector<float>{19, 0, 0, 1}));
      EXPECT_EQ(teammates, (std::vector<float>{3, 0, 0, 1}));
    } else {
      EXPECT_EQ(opponents, (std::vector<float>{19, 0, 0, 1, 0, 22, 0, 1, 0, 0, 0, 0}));
      EXPECT_EQ(teammates, (std::vector<float>{3, 0, 0, 1, 0, 10, 0, 1, 0, 0, 0, 0}));
    }
  }
}

TEST(EnvBatch, EachAgentsObservationEndsWithItsOwnSensorsSegmentsThenZeros) {
  // Pursuers with 8 x 2 rays to 12 m, evaders with 4 x 1 to 6 m: each agent's table ends with its own lidar's
  // segment; the rows are as long as the pursuers' observation, an evader's ending in 12 zeros.
  game::GameConfig c = standing_evaders();
  c.pursuer.sensors.lidar.azimuth_rays = 8, c.pursuer.sensors.lidar.elevation_rays = 2, c.pursuer.sensors.lidar.elevation_fov = 40;
  c.pursuer.sensors.lidar.range = 12;
  c.evader.sensors.lidar.azimuth_rays = 4, c.evader.sensors.lidar.range = 6;
  Batch batch(arena(), c, settings(3, 2));
  Buffers buf{batch};
  const int offset = game::kObservationBase + 2 * 2 * 4;
  ASSERT_EQ(batch.observation_size(), offset + 16);
  for (const auto& [i, rays, range] : {std::tuple{0, 16, 12.0f}, std::tuple{3, 4, 6.0f}}) {
    const game::ObservationTable& t = batch.observation_table(i);
    const sense::Segment* seg = t.find("lidar.ranges");
    ASSERT_NE(seg, nullptr);
    EXPECT_EQ(seg->offset, offset);
    EXPECT_EQ(seg->size, rays);
    EXPECT_EQ(seg->unit, "m");
    EXPECT_EQ(t.size(), offset + rays);
    EXPECT_EQ(&t.segments.back(), seg);
    const ObservationBounds bounds = batch.observation_bounds(i);
    ASSERT_EQ(int(bounds.low.size()), t.size());
    for (int k = offset; k < t.size(); ++k) {
      EXPECT_LT(bounds.low[std::size_t(k)], 0.0f);
      EXPECT_GT(bounds.high[std::size_t(k)], range);
      EXPECT_LT(bounds.high[std::size_t(k)], range + 0.0001f);
    }
  }
  EXPECT_EQ(batch.observation_table(1).find("lidar.ranges")->shape, (std::vector<int>{2, 8}));  // rows of elevation
  const std::vector<double> zeros(3 * 4 * 2, 0.0);
  int echoes = 0;
  for (int step = 0; step <= crash_step() + 2; ++step) {
    for (int g = 0; g < 3; ++g) {
      const game::SimState& st = batch.state(g);
      for (int i = 0; i < 4; ++i) {
        SCOPED_TRACE(::testing::Message() << "step " << step << ", game " << g << ", agent " << i);
        const std::vector<float> o = buf.observation(g, i);
        EXPECT_EQ(std::vector<float>(o.begin(), o.begin() + offset), expected_observation(st, i, 2));
        const sense::Reading* r = st.reading(i, "lidar");
        ASSERT_NE(r, nullptr);
        for (int k = 0; k < 16; ++k) {
          const float want = k < int(r->values.size()) ? float(r->values[std::size_t(k)]) : 0.0f;
          EXPECT_EQ(o[std::size_t(offset + k)], want) << "ray " << k;
          if (k < int(r->values.size())) echoes += r->echo[std::size_t(k)];
        }
      }
    }
    batch.step(zeros.data());
  }
  EXPECT_GT(echoes, 0);  // the rock and the arena's faces were seen, not only the lidars' ranges
}

TEST(EnvBatch, EachStepWritesItsGamesEventsIntoTheBuffers) {
  // Every buffer entry of every step against what the game's own state says the step did; the three starts
  // make sure that captures, crashes, the time limit and agents out of the game all occur.
  Batch batch(arena(), standing_evaders(), settings(3, 2));
  Buffers buf{batch};
  const std::vector<double> zero(std::size_t(3 * 4 * 2), 0.0);
  int captured = 0, collided = 0, terminated = 0, truncated = 0, idle = 0, out = 0;
  for (int k = 1; k <= kLimitSteps + 2; ++k) {
    batch.step(zero.data());
    for (int g = 0; g < 3; ++g) {
      if (buf.reset(g)) continue;  // the autoreset test's business
      const game::SimState& st = batch.state(g);
      const game::StepEvents& ev = st.events;
      for (int i = 0; i < 4; ++i) {
        SCOPED_TRACE(::testing::Message() << "step " << k << ", game " << g << ", agent " << i);
        const game::AgentEvents& e = ev.agents[std::size_t(i)];
        EXPECT_EQ(buf.reward(g, i), float(e.reward.total));
        EXPECT_EQ(buf.term(g, i, 0), float(e.reward.obstacle));
        EXPECT_EQ(buf.term(g, i, 1), float(e.reward.target));
        EXPECT_EQ(buf.term(g, i, 2), float(e.reward.success));
        EXPECT_EQ(buf.acted(g, i), e.acted);
        EXPECT_EQ(buf.collided(g, i), e.collided);
        EXPECT_EQ(buf.captured(g, i), e.captured);
        // Ended for it: its own end (its capture) or the game's; cut by the time limit otherwise.
        EXPECT_EQ(buf.terminated(g, i), e.acted && (e.terminal || ev.terminal));
        EXPECT_EQ(buf.truncated(g, i), e.acted && !e.terminal && !ev.terminal && ev.truncated);
        EXPECT_EQ(buf.active(g, i), st.agents[std::size_t(i)].active && !st.done);
        EXPECT_EQ(buf.observation(g, i), expected_observation(st, i, 2));
        captured += buf.captured(g, i), collided += buf.collided(g, i), terminated += buf.terminated(g, i);
        truncated += buf.truncated(g, i), idle += !buf.acted(g, i), out += !buf.active(g, i);
      }
    }
  }
  EXPECT_GT(captured, 0);
  EXPECT_GT(collided, 0);
  EXPECT_GT(terminated, 0);
  EXPECT_GT(truncated, 0);
  EXPECT_GT(idle, 0);
  EXPECT_GT(out, 0);
}

TEST(EnvBatch, FlagsMarkTheCaptureTheCrashAndTheTimeLimitAtTheirSteps) {
  // Game g's first episode plays start g: capture, crash, timeout. Expected flags per step from the geometry.
  ASSERT_EQ(capture_step(), 82);
  ASSERT_EQ(crash_step(), 48);
  Batch batch(arena(), standing_evaders(), settings(3, 3));
  Buffers buf{batch};
  const std::vector<double> zero(std::size_t(3 * 4 * 2), 0.0);
  const double gamma_s = standing_evaders().pursuer.reward.gamma_s;
  for (int k = 1; k <= kLimitSteps; ++k) {
    batch.step(zero.data());
    SCOPED_TRACE(::testing::Message() << "step " << k);
    // capture: E0 (agent 2) is caught at capture_step and out of the game after; the limit cuts the others.
    for (int i = 0; i < 4; ++i) {
      const bool e0 = i == 2;
      EXPECT_EQ(buf.captured(kCapture, i), e0 && k == capture_step()) << "agent " << i;
      EXPECT_EQ(buf.terminated(kCapture, i), e0 && k == capture_step()) << "agent " << i;
      EXPECT_EQ(buf.acted(kCapture, i), !e0 || k <= capture_step()) << "agent " << i;
      EXPECT_EQ(buf.active(kCapture, i), !(e0 && k >= capture_step()) && k < kLimitSteps) << "agent " << i;
      EXPECT_EQ(buf.truncated(kCapture, i), !e0 && k == kLimitSteps) << "agent " << i;
      EXPECT_FALSE(buf.collided(kCapture, i)) << "agent " << i;
    }
    // The capture's term: +gamma_s for the capturer P0, -gamma_s for E0 (individual capture reward).
    EXPECT_EQ(buf.term(kCapture, 0, 2), k == capture_step() ? float(gamma_s) : 0.0f);
    EXPECT_EQ(buf.term(kCapture, 2, 2), k == capture_step() ? -float(gamma_s) : 0.0f);
    EXPECT_EQ(buf.term(kCapture, 1, 2), 0.0f);
    // crash: P0 hits the rock at crash_step, which ends the game for everyone.
    if (k <= crash_step()) {
      for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(buf.collided(kCrash, i), i == 0 && k == crash_step()) << "agent " << i;
        EXPECT_EQ(buf.terminated(kCrash, i), k == crash_step()) << "agent " << i;
        EXPECT_EQ(buf.active(kCrash, i), k < crash_step()) << "agent " << i;
        EXPECT_TRUE(buf.acted(kCrash, i)) << "agent " << i;
        EXPECT_FALSE(buf.truncated(kCrash, i)) << "agent " << i;
        EXPECT_FALSE(buf.captured(kCrash, i)) << "agent " << i;
      }
    }
    // timeout: nothing but the time limit.
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(buf.truncated(kTimeout, i), k == kLimitSteps) << "agent " << i;
      EXPECT_EQ(buf.active(kTimeout, i), k < kLimitSteps) << "agent " << i;
      EXPECT_TRUE(buf.acted(kTimeout, i)) << "agent " << i;
      EXPECT_FALSE(buf.terminated(kTimeout, i) || buf.collided(kTimeout, i) || buf.captured(kTimeout, i)) << "agent " << i;
    }
    EXPECT_FALSE(buf.reset(kCapture) || buf.reset(kTimeout));
  }
}

TEST(EnvBatch, AnEndedGameIsResetByTheNextStepWhichIgnoresItsActions) {
  const std::uint64_t seed = 11;
  Batch batch(arena(), standing_evaders(), settings(3, 2, seed));
  Buffers buf{batch};
  std::vector<double> actions(std::size_t(3 * 4 * 2), 0.0);
  for (int k = 0; k < crash_step(); ++k) batch.step(actions.data());
  ASSERT_TRUE(batch.state(kCrash).done);
  ASSERT_FALSE(batch.state(kCapture).done || batch.state(kTimeout).done);
  // Actions the step would refuse, for the crashed game only: it is reset, so they are never read.
  std::fill(actions.begin() + 8 * kCrash, actions.begin() + 8 * (kCrash + 1), kNaN);
  ASSERT_NO_THROW(batch.step(actions.data()));

  expect_fresh(batch, buf, kCrash);
  EXPECT_EQ(batch.episode(kCrash), 1);
  // Its second episode starts as a fresh state does from the scenario and seed that episode 1 of game 1 gets.
  const world::Scenario& next = arena()->map().scenarios[(kCrash + 1) % 3];
  game::SimState fresh(batch.sim());
  game::reset(batch.sim(), fresh, next, derive_seed(seed, {std::uint64_t(kCrash), 1}));
  EXPECT_EQ(positions(batch.state(kCrash)), positions(fresh));
  EXPECT_EQ(batch.state(kCrash).step, 0);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(buf.observation(kCrash, i), expected_observation(fresh, i, 2)) << "agent " << i;
  // The others were stepped.
  for (const int g : {kCapture, kTimeout}) {
    EXPECT_FALSE(buf.reset(g)) << "game " << g;
    EXPECT_EQ(batch.state(g).step, crash_step() + 1) << "game " << g;
    EXPECT_EQ(batch.episode(g), 0) << "game " << g;
    EXPECT_TRUE(buf.acted(g, 0)) << "game " << g;
  }
}

TEST(EnvBatch, EachEpisodeStartsFromTheScenarioOfItsGameAndNumber) {
  // No scenario named: episode e of game g plays scenario (g + e) mod 3. Named: every episode plays it.
  const auto& all = arena()->map().scenarios;
  for (const std::string named : {"", "timeout"}) {
    SCOPED_TRACE("scenario '" + named + "'");
    BatchSettings s = settings(4, 2);
    s.scenarios = named.empty() ? std::vector<std::string>{} : std::vector<std::string>{named};
    Batch batch(arena(), standing_evaders(), s);
    Buffers buf{batch};
    const auto expected_start = [&](int g) {
      const std::size_t index = named.empty() ? std::size_t((g + batch.episode(g)) % 3) : std::size_t(kTimeout);
      return start_positions(all[index]);
    };
    for (int g = 0; g < 4; ++g) EXPECT_EQ(positions(batch.state(g)), expected_start(g)) << "game " << g;
    const std::vector<double> zero(std::size_t(4 * 4 * 2), 0.0);
    int restarts = 0;
    for (int k = 0; k < 2 * kLimitSteps + 2; ++k) {
      batch.step(zero.data());
      for (int g = 0; g < 4; ++g) {
        if (!buf.reset(g)) continue;
        ++restarts;
        EXPECT_EQ(positions(batch.state(g)), expected_start(g)) << "game " << g << ", episode " << batch.episode(g);
      }
    }
    EXPECT_GE(restarts, 4);  // every game started a second episode
  }
}

TEST(EnvBatch, WithNoScenarioNamedTheScenariosWithTheFirstOnesTeamsTakeTurns) {
  // 2 v 2, 1 v 1, 2 v 2, 2 v 1: one batch's arrays have one shape, so the 2 v 2 starts play, in turn; the others
  // play when named.
  auto mixed = starts();
  mixed.insert(mixed.begin() + 1, team("duel", {{5, 5, 5}}, {{30, 30, 15}}));
  mixed.push_back(team("2v1", {{5, 5, 5}, {5, 30, 5}}, {{30, 30, 15}}));
  const auto map = testing::make_arena(kSize, {kRock}, mixed, 0.5);
  BatchSettings s = settings(4, 1);
  Batch all(map, standing_evaders(), s);
  EXPECT_EQ(all.scenario_names(), (std::vector<std::string>{"capture", "crash", "timeout"}));
  EXPECT_EQ(all.agents(), 4);
  for (int g = 0; g < 4; ++g) {
    EXPECT_EQ(positions(all.state(g)), start_positions(mixed[g % 3 == 0 ? 0 : std::size_t(g % 3 + 1)])) << g;
  }
  for (const auto& [named, agents] : {std::pair{"duel", 2}, std::pair{"2v1", 3}}) {
    s.scenarios = {named};
    Batch one(map, standing_evaders(), s);
    EXPECT_EQ(one.scenario_names(), std::vector<std::string>{named});
    EXPECT_EQ(one.agents(), agents);
  }
}

TEST(EnvBatch, NamedScenariosTakeTurnsInTheirOrderAndARepeatedOnePlaysAsOftenAsItIsNamed) {
  // ["timeout", "capture", "timeout"]: episode e of game g plays the (g + e) mod 3-th name, so timeout twice as
  // often; a name that is not the map's, or a start with other teams than the first named, is refused.
  const auto& all = arena()->map().scenarios;
  const std::vector<Start> order{kTimeout, kCapture, kTimeout};
  BatchSettings s = settings(5, 2);
  s.scenarios = {"timeout", "capture", "timeout"};
  Batch batch(arena(), standing_evaders(), s);
  EXPECT_EQ(batch.scenario_names(), s.scenarios);
  Buffers buf{batch};
  const auto expected_start = [&](int g) {
    return start_positions(all[std::size_t(order[std::size_t((g + batch.episode(g)) % 3)])]);
  };
  std::array<int, 3> episodes_of{};
  for (int g = 0; g < 5; ++g) {
    EXPECT_EQ(positions(batch.state(g)), expected_start(g)) << "game " << g;
    ++episodes_of[std::size_t(order[std::size_t(g % 3)])];
  }
  const std::vector<double> zero(std::size_t(5 * 4 * 2), 0.0);
  for (int k = 0; k < 3 * kLimitSteps + 3; ++k) {
    batch.step(zero.data());
    for (int g = 0; g < 5; ++g) {
      if (!buf.reset(g)) continue;
      EXPECT_EQ(positions(batch.state(g)), expected_start(g)) << "game " << g << ", episode " << batch.episode(g);
      ++episodes_of[std::size_t(order[std::size_t((g + batch.episode(g)) % 3)])];
    }
  }
  EXPECT_EQ(episodes_of[kCrash], 0);
  EXPECT_GT(episodes_of[kTimeout], episodes_of[kCapture]);

  s.scenarios = {"timeout", "nowhere"};
  EXPECT_THROW(Batch(arena(), standing_evaders(), s), InvalidParameter);
  auto mixed = starts();
  mixed.push_back(team("duel", {{5, 5, 5}}, {{30, 30, 15}}));
  s.scenarios = {"timeout", "duel"};
  EXPECT_THROW(Batch(testing::make_arena(kSize, {kRock}, mixed, 0.5), standing_evaders(), s), InvalidParameter);
}

// The caller's actions for step k: different for every game, agent and step, within the steering bound.
std::vector<double> varied_actions(int games, int agents, int k) {
  std::vector<double> a(std::size_t(games * agents * 2));
  for (int g = 0; g < games; ++g) {
    for (int i = 0; i < agents; ++i) {
      double* x = a.data() + 2 * (g * agents + i);
      x[0] = 0.02 * (i + 1) * (g + 1) * (k % 2 == 0 ? 1 : -1);
      x[1] = 0.01 * std::sin(0.3 * k + i);
    }
  }
  return a;
}

TEST(EnvBatch, EveryGlobalStateEntryLiesWithinItsBoundsThroughWholeEpisodes) {
  // Every agent flying and steering hard off its chase heading, crashes, captures and time limits: two episodes
  // of each game.
  game::GameConfig everyone_flies = standing_evaders();
  everyone_flies.evader = game::preset("peg3d").evader;
  Batch batch(arena(), everyone_flies, settings(4, 1));
  const auto [low, high] = batch.state_bounds();
  ASSERT_EQ(int(low.size()), batch.global_state_size());
  ASSERT_EQ(int(high.size()), batch.global_state_size());
  EXPECT_FLOAT_EQ(high.back(), float(kLimitSteps * 0.1 + 0.1));
  double latest = 0.0;
  for (int k = 0; k < 2 * kLimitSteps + 2; ++k) {
    // Hard turns at the steering bound, each agent always the same way.
    const double bound = std::min(batch.action_bound(Role::kPursuer), batch.action_bound(Role::kEvader));
    std::vector<double> a(std::size_t(4 * 4 * 2));
    for (std::size_t j = 0; j < a.size(); j += 2) {
      a[j] = (j / 2) % 2 == 0 ? bound : -bound;
      a[j + 1] = ((j / 2) % 3 == 0 ? 0.2 : -0.2) * bound;
    }
    batch.step(a.data());
    for (int g = 0; g < 4; ++g) {
      const std::vector<float> st = batch.global_state(g);
      for (std::size_t e = 0; e < st.size(); ++e) {
        ASSERT_GE(st[e], low[e]) << "game " << g << ", step " << k << ", entry " << e;
        ASSERT_LE(st[e], high[e]) << "game " << g << ", step " << k << ", entry " << e;
      }
      latest = std::max(latest, double(st.back()));
    }
  }
  EXPECT_GE(latest, kLimitSteps * 0.1 - 1e-6);  // a game reached its time limit
}

TEST(EnvBatch, AClassicPolicyNamedForAnAgentPlaysItInsteadOfTheCallersActions) {
  // evader_0 flees on the C++ side; the caller steers the others. Each game must follow, bit for bit, a state
  // stepped here with the same commands and a flee policy of its own for evader_0.
  game::GameConfig c = standing_evaders();
  c.evader.speed = 1.0;
  c.initial_heading = game::InitialHeading::kRandom;  // from each game's episode seed
  BatchSettings s = settings(2, 2, 21);
  s.scenarios = {"timeout"};
  s.controllers = {{"evader_0", {{"flee"}}}};
  Batch batch(arena(), c, s);
  EXPECT_TRUE(batch.controlled(2));
  EXPECT_FALSE(batch.controlled(0) || batch.controlled(1) || batch.controlled(3));
  game::AgentConfig flee_config = batch.sim().config().agent(Role::kEvader, 0);
  flee_config.policy = "flee";
  std::vector<std::unique_ptr<game::SimState>> refs;
  std::vector<std::unique_ptr<game::Policy>> flee;
  for (int g = 0; g < 2; ++g) {
    refs.push_back(std::make_unique<game::SimState>(batch.sim()));
    game::reset(batch.sim(), *refs.back(), arena()->map().scenarios[kTimeout], derive_seed(21, {std::uint64_t(g), 0}));
    flee.push_back(players::make_player(flee_config, Role::kEvader, 0));
    flee.back()->begin_episode(game::observe(*refs.back(), 2), false);
  }
  int turns = 0;
  for (int k = 1; k <= 40; ++k) {
    std::vector<double> actions = varied_actions(2, 4, k);
    for (int g = 0; g < 2; ++g) actions[std::size_t(8 * g + 4)] = actions[std::size_t(8 * g + 5)] = kNaN;  // never read
    std::vector<double> refused = actions;
    refused[8 + 7] = kNaN;  // game 1's evader_1 is the caller's: refused before anything acts or steps
    const std::vector<Vec3> before0 = positions(batch.state(0)), before1 = positions(batch.state(1));
    const game::CommandError e = refusal(batch, refused);
    EXPECT_EQ(e.game(), 1);
    EXPECT_EQ(e.agent(), 3);
    EXPECT_EQ(e.step(), k);
    ASSERT_EQ(positions(batch.state(0)), before0);
    ASSERT_EQ(positions(batch.state(1)), before1);
    batch.step(actions.data());
    for (int g = 0; g < 2; ++g) {
      game::SimState& ref = *refs[std::size_t(g)];
      std::vector<Steering> commands(4);
      for (const int i : {0, 1, 3}) {
        commands[std::size_t(i)] = {actions[std::size_t(8 * g + 2 * i)], actions[std::size_t(8 * g + 2 * i + 1)]};
      }
      commands[2] = flee[std::size_t(g)]->act(game::observe(ref, 2));
      turns += commands[2].d_alpha != 0.0 || commands[2].d_theta != 0.0;
      game::step(batch.sim(), ref, commands);
      ASSERT_FALSE(ref.done);
      ASSERT_EQ(positions(batch.state(g)), positions(ref)) << "step " << k << ", game " << g;
    }
  }
  EXPECT_GT(turns, 0);  // flee steered: a batch that flew evader_0 straight would differ
}

// The members of the first `games` games' first episodes, re-seeded with seeds first, first + 1, ...: games x agents.
std::vector<int> members_over_seeds(Batch& batch, int first, int count) {
  std::vector<int> out;
  for (int k = 0; k < count; ++k) {
    batch.reset_game(0, std::uint64_t(first + k));
    for (int i = 0; i < batch.agents(); ++i) out.push_back(batch.member(0, i));
  }
  return out;
}

TEST(EnvBatch, AMixtureDrawsItsMembersByWeightEachEpisodeAndARolesAgentsTogether) {
  // The evaders' mixture: flee 3, random 1, hide 0 (never drawn). Over 4000 seeds the first member's share is
  // 0.75 within 5 standard deviations (0.034), both evaders always play the same member, and the pursuers,
  // left to the caller, none.
  BatchSettings s = settings(1);
  s.controllers = {{"evader", {{"flee", 3.0}, {"random", 1.0}, {"hide", 0.0}}}};
  Batch batch(arena(), standing_evaders(), s);
  EXPECT_FALSE(batch.controlled(0) || batch.controlled(1));
  EXPECT_TRUE(batch.controlled(2) && batch.controlled(3));
  ASSERT_EQ(batch.mixture(2).size(), 3u);
  EXPECT_EQ(batch.mixture(2)[1].policy, "random");
  const int n = 4000;
  const std::vector<int> m = members_over_seeds(batch, 0, n);
  std::array<int, 3> count{};
  for (int k = 0; k < n; ++k) {
    ASSERT_EQ(m[std::size_t(4 * k)], -1);
    ASSERT_EQ(m[std::size_t(4 * k + 1)], -1);
    ASSERT_EQ(m[std::size_t(4 * k + 2)], m[std::size_t(4 * k + 3)]) << "seed " << k;
    ++count[std::size_t(m[std::size_t(4 * k + 2)])];
  }
  EXPECT_EQ(count[2], 0);
  EXPECT_NEAR(double(count[0]) / n, 0.75, 5 * std::sqrt(0.75 * 0.25 / n));

  // Within one game the draw changes from episode to episode (not once per game), from the seed alone.
  batch.reset(5);
  std::array<int, 2> per_episode{};
  for (int e = 0; e < 400; ++e) {
    ++per_episode[std::size_t(batch.member(0, 2))];
    batch.reset();
  }
  EXPECT_NEAR(per_episode[0] / 400.0, 0.75, 5 * std::sqrt(0.75 * 0.25 / 400));
}

TEST(EnvBatch, AgentsNamedOneByOneDrawTheirMixturesApartAndTheDrawsFollowTheSeedNotTheThreads) {
  // evader_1 overrides the role's mixture with its own: the two evaders draw apart (they differ in some
  // episodes). Five games on 1 and on 3 threads draw the same members, episode after episode.
  std::vector<std::vector<int>> runs;
  for (const int threads : {1, 3}) {
    BatchSettings s = settings(5, threads, 77);
    s.controllers = {{"evader", {{"flee", 1.0}, {"random", 1.0}}}, {"evader_1", {{"flee", 1.0}, {"random", 1.0}}}};
    Batch batch(arena(), standing_evaders(), s);
    std::vector<int> seen;
    const std::vector<double> zero(std::size_t(5 * 4 * 2), 0.0);
    for (int k = 0; k < 3 * kLimitSteps; ++k) {
      batch.step(zero.data());
      for (int g = 0; g < 5; ++g) {
        for (int i = 0; i < 4; ++i) seen.push_back(batch.member(g, i));
      }
    }
    runs.push_back(seen);
  }
  EXPECT_EQ(runs[0], runs[1]);
  int apart = 0;
  for (std::size_t k = 0; k < runs[0].size(); k += 4) apart += runs[0][k + 2] != runs[0][k + 3];
  EXPECT_GT(apart, 0);
}

TEST(EnvBatch, AMixturesDrawnMemberPlaysAsThatPlayerAlone) {
  // Evaders drawn from {flee, random}: in the episodes that drew flee, every step equals a batch whose evaders
  // all flee (the same episode seeds); in those that drew random, the evaders go elsewhere.
  game::GameConfig c = standing_evaders();
  c.evader.speed = 1.0;
  BatchSettings s = settings(1, 1, 3);
  s.scenarios = {"timeout"};
  BatchSettings alone = s;
  s.controllers = {{"evader", {{"flee", 1.0}, {"random", 1.0}}}};
  alone.controllers = {{"evader", {{"flee"}}}};
  Batch mixed(arena(), c, s), flee(arena(), c, alone);
  std::array<int, 2> same{}, episodes{};
  const std::vector<double> zero(std::size_t(4 * 2), 0.0);
  for (int seed = 0; seed < 12; ++seed) {
    mixed.reset_game(0, std::uint64_t(seed));
    flee.reset_game(0, std::uint64_t(seed));
    const int member = mixed.member(0, 2);
    ASSERT_EQ(flee.member(0, 2), 0);
    bool equal = true;
    for (int k = 0; k < 30; ++k) {
      mixed.step(zero.data());
      flee.step(zero.data());
      equal = equal && positions(mixed.state(0)) == positions(flee.state(0));
    }
    ++episodes[std::size_t(member)];
    same[std::size_t(member)] += equal;
  }
  ASSERT_GT(episodes[0], 0);
  ASSERT_GT(episodes[1], 0);
  EXPECT_EQ(same[0], episodes[0]);
  EXPECT_EQ(same[1], 0);
}

TEST(EnvBatch, AClassicMemberPlaysFreeOfTheMotionSpaceAsTheExperimentsPlayIt) {
  // peg3d's pursuers keep their heading in the motion space; the experiments play a classic pursuer without it
  // (game::with_role_playing). Pursuers drawn from {pn, pure-pursuit} against the caller's evaders must follow, bit
  // for bit, the drawn member played in a Sim made as the experiments make it; and the same member held by the
  // motion space must part from it in some episode (else the test could not tell).
  game::GameConfig c = standing_evaders();
  c.evader.speed = 1.0;
  c.initial_heading = game::InitialHeading::kRandom;
  ASSERT_TRUE(c.pursuer.motion_space);
  BatchSettings s = settings(1, 1, 9);
  s.scenarios = {"timeout"};
  s.controllers = {{"pursuer", {{"pn", 1.0}, {"pure-pursuit", 1.0}}}};
  Batch batch(arena(), c, s);
  const world::Scenario& start = arena()->map().scenarios[kTimeout];
  std::array<int, 2> episodes{};
  int parted = 0;
  for (int seed = 0; seed < 8; ++seed) {
    batch.reset_game(0, std::uint64_t(seed));
    const int member = batch.member(0, 0);
    ASSERT_EQ(batch.member(0, 1), member);
    const std::string name = member == 0 ? "pn" : "pure-pursuit";
    ++episodes[std::size_t(member)];
    const game::Sim free_sim(arena(), game::with_role_playing(c, Role::kPursuer, name));
    game::SimState free_state(free_sim), held_state(batch.sim());
    // A mixture's member is seeded by its place (env/batch.hpp); the classic pursuers here draw nothing.
    std::vector<std::unique_ptr<game::Policy>> free_players, held_players;
    for (int i = 0; i < 2; ++i) {
      const game::AgentConfig& a = free_sim.config().agent(Role::kPursuer, i);
      free_players.push_back(players::make_player(a, Role::kPursuer, 0));
      held_players.push_back(std::make_unique<testing::Unscripted>(players::make_player(a, Role::kPursuer, 0)));
    }
    const std::uint64_t episode_seed = derive_seed(std::uint64_t(seed), {0, 0});
    game::reset(free_sim, free_state, start, episode_seed);
    game::reset(batch.sim(), held_state, start, episode_seed);
    for (int i = 0; i < 2; ++i) {
      game::begin_playing(free_sim, free_state, i, *free_players[std::size_t(i)], false);
      game::begin_playing(batch.sim(), held_state, i, *held_players[std::size_t(i)], false);
    }
    bool apart = false;
    for (int k = 1; k <= 60 && !free_state.done && !held_state.done; ++k) {
      const std::vector<double> actions = varied_actions(1, 4, k);
      std::vector<Steering> free_commands(4), held_commands(4);
      for (const int i : {2, 3}) {
        free_commands[std::size_t(i)] = held_commands[std::size_t(i)] = {actions[std::size_t(2 * i)],
                                                                         actions[std::size_t(2 * i + 1)]};
      }
      for (const int i : {0, 1}) {
        free_commands[std::size_t(i)] = free_players[std::size_t(i)]->act(game::observe(free_state, i));
        held_commands[std::size_t(i)] = held_players[std::size_t(i)]->act(game::observe(held_state, i));
      }
      batch.step(actions.data());
      game::step(free_sim, free_state, free_commands);
      game::step(batch.sim(), held_state, held_commands);
      ASSERT_EQ(positions(batch.state(0)), positions(free_state)) << "seed " << seed << " (" << name << "), step " << k;
      apart = apart || positions(held_state) != positions(free_state);
    }
    parted += apart;
  }
  EXPECT_GT(episodes[0], 0);
  EXPECT_GT(episodes[1], 0);
  EXPECT_GT(parted, 0);
}

TEST(EnvBatch, AMixtureIsRefusedNamingTheMemberOrWeightAtFault) {
  const std::string dir = std::string(PEG3D_TEST_DATA_DIR) + "/policies/";
  const auto refused = [](std::vector<MixtureEntry> mixture) {
    BatchSettings s = settings(1);
    s.controllers = {{"evader", std::move(mixture)}};
    try {
      Batch batch(arena(), standing_evaders(), s);
    } catch (const InvalidParameter& e) {
      return e.parameter();
    } catch (const InputError& e) {
      return std::string("input error: ") + e.what();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused({{"flee", 1.0}, {"random", -1.0}}), "opponents.evader.1.weight");
  EXPECT_EQ(refused({{"flee", 1.0}, {"random", kNaN}}), "opponents.evader.1.weight");
  EXPECT_EQ(refused({{"flee", 1.0}, {"random", kInf}}), "opponents.evader.1.weight");
  EXPECT_EQ(refused({{"flee", 0.0}, {"random", 0.0}}), "opponents.evader");
  EXPECT_EQ(refused({{"flee", 1e308}, {"random", 1e308}}), "opponents.evader");  // the total overflows
  EXPECT_EQ(refused({{"flee", 1.0}, {"no-such-player", 1.0}}), "opponents.evader.1");
  EXPECT_EQ(refused({{"flee", 1.0}, {"pure-pursuit", 1.0}}), "opponents.evader.1");  // a pursuer's player
  EXPECT_EQ(refused({{"flee", 1.0}, {"", 1.0}}), "opponents.evader.1");
  EXPECT_EQ(refused(std::vector<MixtureEntry>(std::size_t(kMaxMixtureEntries) + 1, MixtureEntry{"flee", 1.0})),
            "opponents.evader");
  EXPECT_EQ(refused(std::vector<MixtureEntry>(std::size_t(kMaxMixtureEntries), MixtureEntry{"flee", 1.0})), "accepted");
  // Two FACL files of different agent configurations cannot play one agent; the same file twice can.
  nlohmann::json doc;
  std::ifstream(dir + "robust_evader.json") >> doc;
  doc["config"]["speed"] = doc["config"]["speed"].get<double>() * 0.5;
  const std::filesystem::path slower = std::filesystem::path(::testing::TempDir()) / "slower_evader.json";
  std::ofstream(slower) << doc.dump();
  EXPECT_EQ(refused({{dir + "robust_evader.json", 1.0}, {"flee", 1.0}, {slower.string(), 1.0}}), "opponents.evader.2");
  EXPECT_EQ(refused({{dir + "robust_evader.json", 1.0}, {"flee", 1.0}, {dir + "robust_evader.json", 2.0}}), "accepted");
  // A pursuer's file in the evaders' mixture names the file.
  EXPECT_NE(refused({{"flee", 1.0}, {dir + "ppo_pursuer.json", 1.0}}).find("ppo_pursuer.json"), std::string::npos);
}

TEST(EnvBatch, SavedPolicyFilesPlayTheirRolesWithTheirOwnConfiguration) {
  // An MLP file for both pursuers and a FACL file for both evaders: each game's first episode is play()'s with
  // greedy players of those files, from the game's episode seed.
  const std::string dir = std::string(PEG3D_TEST_DATA_DIR) + "/policies/";
  game::GameConfig c = standing_evaders();
  c.initial_heading = game::InitialHeading::kRandom;  // from each game's episode seed
  BatchSettings s = settings(2, 2, 31);
  s.scenarios = {"capture"};
  s.controllers = {{"pursuer", {{dir + "ppo_pursuer.json"}}}, {"evader", {{dir + "robust_evader.json"}}}};
  Batch batch(arena(), c, s);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(batch.controlled(i)) << "agent " << i;
  const auto mlp = players::load_saved_policy(dir + "ppo_pursuer.json", Role::kPursuer);
  const auto facl = players::load_saved_policy(dir + "robust_evader.json", Role::kEvader);
  ASSERT_TRUE(mlp->mlp && facl->facl);
  // A FACL file brings its agent configuration (speed, guard, observation); an MLP plays with the game's.
  EXPECT_TRUE(batch.sim().config().agent(Role::kEvader, 0) == *facl->config());
  EXPECT_TRUE(batch.sim().config().agent(Role::kEvader, 1) == *facl->config());
  EXPECT_TRUE(batch.sim().config().agent(Role::kPursuer, 1) == c.pursuer);
  std::vector<game::Trace> traces(2);
  for (int g = 0; g < 2; ++g) {
    game::SimState ref(batch.sim());
    const game::AgentConfig& pa = batch.sim().config().pursuer;
    const game::AgentConfig& ea = batch.sim().config().evader;
    const auto p0 = mlp->make(0, pa, Role::kPursuer, 0), p1 = mlp->make(0, pa, Role::kPursuer, 0);
    const auto e0 = facl->make(0, ea, Role::kEvader, 0), e1 = facl->make(0, ea, Role::kEvader, 0);
    game::Policy* policies[] = {p0.get(), p1.get(), e0.get(), e1.get()};
    game::play(batch.sim(), ref, arena()->map().scenarios[kCapture], policies, false,
               derive_seed(31, {std::uint64_t(g), 0}), &traces[std::size_t(g)]);
    ASSERT_GT(traces[std::size_t(g)].frame_count(), 20);
  }
  const std::vector<double> ignored(std::size_t(2 * 4 * 2), kNaN);
  for (int k = 1; k < traces[0].frame_count() || k < traces[1].frame_count(); ++k) {
    batch.step(ignored.data());
    for (int g = 0; g < 2; ++g) {
      const game::Trace& t = traces[std::size_t(g)];
      if (k >= t.frame_count()) continue;  // its episode is over
      for (int i = 0; i < 4; ++i) {
        ASSERT_EQ(batch.state(g).agents[std::size_t(i)].kinematics.position, t.at(k, i).state.position)
            << "step " << k << ", game " << g << ", agent " << i;
      }
    }
  }
}

// An MLP file played by sample ("play": "sample"): its draws come from each game's policy seed, so the games play
// the same on any number of threads; they differ from the mean's play, and from game to game.
TEST(EnvBatch, ASampledMlpOpponentPlaysTheSameOnAnyThreadCount) {
  const std::string dir = std::string(PEG3D_TEST_DATA_DIR) + "/policies/";
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(dir + "ppo_pursuer.json"));
  doc["action_std"] = {0.1, 0.1};
  doc["play"] = "sample";
  const std::filesystem::path sampled = std::filesystem::path(::testing::TempDir()) / "sampled_mlp.json";
  std::ofstream(sampled) << doc.dump();
  const auto play = [&](const std::string& file, int threads) {
    BatchSettings s = settings(4, threads, 9);
    s.scenarios = {"timeout"};  // the same start in every game
    s.controllers = {{"pursuer", {{file}}}};
    game::GameConfig c = standing_evaders();
    c.pursuer.motion_space = false;  // its cone about the line to a standing evader would take the draws away
    Batch batch(arena(), c, s);
    const std::vector<double> actions(std::size_t(4 * 4 * 2), 0.0);
    for (int k = 0; k < 30; ++k) batch.step(actions.data());
    std::vector<std::vector<Vec3>> out;
    for (int g = 0; g < 4; ++g) out.push_back(positions(batch.state(g)));
    return out;
  };
  const auto one = play(sampled.string(), 1);
  EXPECT_EQ(one, play(sampled.string(), 2));
  EXPECT_EQ(one, play(sampled.string(), 4));
  EXPECT_NE(one, play(dir + "ppo_pursuer.json", 1));
  EXPECT_NE(one[0], one[1]);
}

// A C++-played MLP whose network overflows (finite weights of +-1e308: inf - inf inside its sum) is refused by
// its game's step, the error naming the game, the agent and the policy file.
TEST(EnvBatch, APlayedPolicyWhoseCommandIsRefusedNamesItsFileAndGame) {
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "overflowing_mlp.json";
  {
    std::ofstream out(file);
    out << R"({"format": "peg3d-mlp", "version": 1, "role": "evader", "inputs": 20, "action_bound": 0.4,)"
        << R"("input_mean": [0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0], "input_std": [)";
    for (int i = 0; i < 20; ++i) out << (i ? ", " : "") << "0.01";
    out << R"(], "layers": [{"bias": [0, 0], "weights": [)";
    for (int j = 0; j < 2; ++j) {
      out << (j ? ", [" : "[");
      for (int i = 0; i < 20; ++i) out << (i ? ", " : "") << (i % 2 ? "-1e308" : "1e308");
      out << "]";
    }
    out << "]}]}";
  }
  BatchSettings s = settings(3, 1, 5);
  s.scenarios = {"timeout"};
  s.controllers = {{"evader_1", {{file.string()}}}};
  Batch batch(arena(), standing_evaders(), s);
  const std::vector<double> actions(std::size_t(3 * 4 * 2), 0.0);
  const game::CommandError e = refusal(batch, actions);
  EXPECT_EQ(e.game(), 0);
  EXPECT_EQ(e.agent(), 3);
  EXPECT_EQ(e.file(), file);
  EXPECT_NE(std::string(e.what()).find("game 0: step 1: agent 3 (evader 1), played by this policy file: steering command ("),
            std::string::npos) << e.what();
  EXPECT_EQ(batch.state(0).step, 0);
}

TEST(EnvBatch, ResetWithASeedStartsOverAsANewBatchOfThatSeed) {
  game::GameConfig c = standing_evaders();
  c.initial_heading = game::InitialHeading::kRandom;
  Batch used(arena(), c, settings(3, 2, 7));
  for (int k = 1; k <= 60; ++k) used.step(varied_actions(3, 4, k).data());
  used.reset(8);
  Batch fresh(arena(), c, settings(3, 2, 8));
  Buffers a{used}, b{fresh};
  for (int g = 0; g < 3; ++g) {
    EXPECT_EQ(used.episode(g), 0) << "game " << g;
    EXPECT_EQ(positions(used.state(g)), positions(fresh.state(g))) << "game " << g;
    for (int i = 0; i < 4; ++i) EXPECT_EQ(a.observation(g, i), b.observation(g, i)) << "game " << g << ", agent " << i;
    expect_fresh(used, a, g);
  }
}

TEST(EnvBatch, AGameReseededAlonePlaysAsGameZeroOfABatchOfThatSeedAndTheOthersGoOn) {
  // Random headings and a random evader_1 on the C++ side: episodes and policies both draw from the seed.
  game::GameConfig c = standing_evaders();
  c.initial_heading = game::InitialHeading::kRandom;
  c.evader.speed = 1.0;
  BatchSettings s = settings(3, 1, 7);
  s.controllers = {{"evader_1", {{"random"}}}};
  Batch mixed(arena(), c, s), untouched(arena(), c, s);
  s.games = 1;
  s.seed = 99;
  Batch alone(arena(), c, s);
  for (int k = 1; k <= 20; ++k) {
    mixed.step(varied_actions(3, 4, k).data());
    untouched.step(varied_actions(3, 4, k).data());
  }
  mixed.reset_game(2, 99);
  EXPECT_EQ(mixed.episode(2), 0);
  EXPECT_EQ(mixed.reset_flags()[2], 1);
  Buffers m{mixed}, a{alone};
  // Past the 10 s time limit: the autoreset's second episode is game 0's second one too.
  for (int k = 21; k <= 21 + kLimitSteps + 30; ++k) {
    std::vector<double> actions = varied_actions(3, 4, k);
    mixed.step(actions.data());
    untouched.step(actions.data());
    alone.step(actions.data() + 2 * 4 * 2);  // game 2's actions
    ASSERT_EQ(positions(mixed.state(2)), positions(alone.state(0))) << "step " << k;
    for (int i = 0; i < 4; ++i) ASSERT_EQ(m.observation(2, i), a.observation(0, i)) << "step " << k;
    for (int g = 0; g < 2; ++g) ASSERT_EQ(positions(mixed.state(g)), positions(untouched.state(g))) << "game " << g;
  }
  EXPECT_EQ(mixed.episode(2), 1);
  // Without a seed: game 1 alone starts its next episode, from the next scenario in its turn.
  const long long before = mixed.episode(1);
  mixed.reset_game(1);
  EXPECT_EQ(mixed.episode(1), before + 1);
  EXPECT_EQ(mixed.episode(0), untouched.episode(0));
  EXPECT_THROW(mixed.reset_game(3), InvalidParameter);
}

// Every buffer and every game's episode number, hashed after reset() and after each of `steps` steps of
// random actions: 13 games over the three starts from random headings, episodes of 3 s (many autoresets),
// evader_1 a random policy seeded per game on the C++ side.
struct HashedRun {
  std::uint64_t hash = 0;
  int restarts = 0;                       // autoresets
  std::size_t blocks_before = 0, blocks_after = 0;  // the movers' timeline: blocks simulated (maps with movers)
};
HashedRun hashed_run(std::shared_ptr<const world::Arena> a, int threads, int steps) {
  game::GameConfig c = standing_evaders();
  c.time_limit = 3.0;
  c.evader.speed = 1.0;
  c.initial_heading = game::InitialHeading::kRandom;
  BatchSettings s = settings(13, threads, 41);
  s.controllers = {{"evader_1", {{"random"}}}};
  Batch batch(std::move(a), c, s);
  const std::size_t n = std::size_t(batch.games()) * std::size_t(batch.agents());
  HashedRun run;
  const auto blocks = [&] { return batch.sim().movers() ? batch.sim().movers()->stats().blocks_simulated : 0; };
  run.blocks_before = blocks();
  Fnv1a h;
  const auto add = [&] {
    h.add(batch.observations(), n * std::size_t(batch.observation_size()) * sizeof(float));
    h.add(batch.rewards(), n * sizeof(float));
    h.add(batch.reward_terms(), 3 * n * sizeof(float));
    for (const std::uint8_t* flags : {batch.terminated(), batch.truncated(), batch.acted(), batch.active(),
                                      batch.collided(), batch.captured()}) {
      h.add(flags, n);
    }
    h.add(batch.reset_flags(), std::size_t(batch.games()));
    for (int g = 0; g < batch.games(); ++g) h.add_value(batch.episode(g));
  };
  add();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> turn(-batch.action_bound(Role::kPursuer), batch.action_bound(Role::kPursuer));
  std::vector<double> actions(2 * n);
  for (int k = 0; k < steps; ++k) {
    for (double& x : actions) x = turn(rng);
    batch.step(actions.data());
    add();
    for (int g = 0; g < batch.games(); ++g) run.restarts += batch.reset_flags()[g];
  }
  run.hash = h.value();
  run.blocks_after = blocks();
  return run;
}

TEST(EnvBatch, BuffersDoNotDependOnTheThreadCount) {
  const HashedRun one = hashed_run(arena(), 1, 150);
  EXPECT_GE(one.restarts, 13 * 4);  // every game played several episodes
  for (const int threads : {2, 3, 7}) EXPECT_EQ(hashed_run(arena(), threads, 150).hash, one.hash) << threads << " threads";
}

// The test arena with movers: a box patrolling through the middle and a ball that Bullet drops to the floor.
// Built afresh for every batch, so that the batch's threads simulate the movers' timeline as they reach it.
std::shared_ptr<const world::Arena> arena_with_movers() {
  world::MapSpec m;
  m.name = "movers";
  m.bounds = {Vec3::Zero(), kSize};
  m.resolution = 0.5;
  m.max_distance = 5.0;
  m.floor_is_obstacle = m.ceiling_is_obstacle = m.walls_is_obstacle = false;
  m.spheres = {kRock};
  world::MoverSpec box;
  box.shape = {Shape::Kind::kBox, 1.0, 1.0, Vec3(2, 2, 2)};
  box.motion = world::MoverSpec::Motion::kPath;
  box.path = {{Vec3(4, 17.5, 5), Vec3(31, 17.5, 5)}, 1.5, false};
  world::MoverSpec ball;
  ball.shape = {Shape::Kind::kSphere, 1.0, 1.0, Vec3::Ones()};
  ball.motion = world::MoverSpec::Motion::kDynamic;
  ball.start = Vec3(20, 25, 15);
  m.movers = {box, ball};
  m.scenarios = starts();
  return world::Arena::build(m);
}

TEST(EnvBatch, BuffersDoNotDependOnTheThreadCountOnAMapWithMovers) {
  const HashedRun one = hashed_run(arena_with_movers(), 1, 60);
  const HashedRun three = hashed_run(arena_with_movers(), 3, 60);
  EXPECT_EQ(three.hash, one.hash);
  // Most of the timeline was simulated by the steps, on the batch's threads (reset() needs its first window).
  EXPECT_GT(three.blocks_after, 2 * three.blocks_before);
}

}  // namespace
}  // namespace peg3d::env
