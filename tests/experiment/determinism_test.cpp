// Golden determinism, in the manner of Box2D's test_determinism.c: fixed-seed training runs on the shipped
// maps, hashed over every instant of every episode (positions, headings, commands, rewards) and over the
// learned tables at the end, compared with hashes kept here. Runs are spread over 1 and 2 threads and must
// give the same hashes. A deliberate change of results updates the constants in the same commit, saying why.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>

#include "core/hash.hpp"
#include "core/random.hpp"
#include "game/episode.hpp"
#include "players/lineup.hpp"
#include "sweep/parallel_runner.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::experiment {
namespace {

// Golden values (their history: docs/results.md, "Golden hashes").
constexpr std::uint64_t kPaperHash = 0x10494b40ad84a1f5; // maps/paper.yaml, peg3d preset, 4 scenarios x 6 training episodes
constexpr std::uint64_t kPackHash = 0xca3128c92953b4c1;  // maps/pack.yaml, peg3d preset, 4 team scenarios x 3 training episodes
constexpr std::uint64_t kPatrolHash = 0x9e487d558b277845; // maps/patrol.yaml (scripted movers), 4 scenarios x 2 episodes
// maps/pack.yaml and maps/patrol.yaml with limited sight (240 deg, dead-reckoned and shared by the pursuers)
constexpr std::uint64_t kSightHash = 0x686419af1f281155;
constexpr std::uint64_t kRockfallHash = 0x95c142525eb4321a; // maps/rockfall.yaml (Bullet's boulders), 3 scenarios x 2 episodes

void hash_trace(Fnv1a& h, const game::Trace& t) {
  for (int k = 0; k < t.frame_count(); ++k) {
    h.add_value(t.times[std::size_t(k)]);
    for (int i = 0; i < t.agents; ++i) {
      const game::AgentFrame& f = t.at(k, i);
      h.add_value(f.state.position.x());
      h.add_value(f.state.position.y());
      h.add_value(f.state.position.z());
      h.add_value(f.state.heading.alpha);
      h.add_value(f.state.heading.theta);
      h.add_value(f.command.d_alpha);
      h.add_value(f.command.d_theta);
      h.add_value(f.reward);
      h.add_value(f.active);
    }
  }
  for (const auto& c : t.captures) h.add_value(c.step), h.add_value(c.pursuer), h.add_value(c.evader);
  for (const auto& c : t.collisions) h.add_value(c.step), h.add_value(c.agent), h.add_value(c.obstacle_id);
}

// One job: a scenario's agents train for `episodes` episodes; the hash of every step and of the tables.
std::uint64_t train_and_hash(const game::Sim& sim, const world::Scenario& s, std::uint64_t seed, int episodes) {
  players::Lineup lineup;
  players::RoleModels pursuers, evaders;
  players::add_configured(lineup, sim.config(), game::Role::kPursuer, static_cast<int>(s.pursuers.size()),
                       derive_seed(seed, {1}), &pursuers);
  players::add_configured(lineup, sim.config(), game::Role::kEvader, static_cast<int>(s.evaders.size()),
                       derive_seed(seed, {2}), &evaders);
  game::SimState state(sim);
  game::Trace trace;
  trace.reserve(sim.max_steps(), s.agents());
  Fnv1a h;
  for (int e = 0; e < episodes; ++e) {
    const game::EpisodeResult r =
        game::play(sim, state, s, lineup.policies(), true, derive_seed(seed, {3, std::uint64_t(e)}), &trace);
    hash_trace(h, trace);
    h.add_value(r.steps);
    h.add_value(static_cast<int>(r.outcome));
  }
  for (const players::RoleModels* models : {&pursuers, &evaders}) {
    for (const auto& m : models->models) {
      for (int c = 0; c < m->channels(); ++c) {
        h.add_span(m->tables(c).actor_table());
        h.add_span(m->tables(c).critic_table());
      }
    }
  }
  return h.value();
}

std::uint64_t sweep_hash(const char* map, int episodes, int threads, const game::GameConfig& config = game::preset("peg3d")) {
  const auto arena = world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/" + map));
  const game::Sim sim(arena, config);
  const auto& scenarios = arena->map().scenarios;
  std::vector<std::uint64_t> hashes(scenarios.size());
  sweep::run_indexed(scenarios.size(), threads, [&](std::size_t i) {
    hashes[i] = train_and_hash(sim, scenarios[i], derive_seed(2024, {i}), episodes);
  });
  Fnv1a all;
  for (const std::uint64_t v : hashes) all.add_value(v);
  return all.value();
}

TEST(ExperimentDeterminism, PaperMapTrainingMatchesTheGoldenHashOnOneAndTwoThreads) {
  const std::uint64_t one = sweep_hash("maps/paper.yaml", 6, 1);
  const std::uint64_t two = sweep_hash("maps/paper.yaml", 6, 2);
  std::printf("paper hash 0x%016" PRIx64 "\n", one);
  EXPECT_EQ(one, two);
  EXPECT_EQ(one, kPaperHash) << std::hex << "0x" << one;
}

TEST(ExperimentDeterminism, TeamTrainingMatchesTheGoldenHashOnOneAndTwoThreads) {
  const std::uint64_t one = sweep_hash("maps/pack.yaml", 3, 1);
  const std::uint64_t two = sweep_hash("maps/pack.yaml", 3, 2);
  std::printf("pack hash 0x%016" PRIx64 "\n", one);
  EXPECT_EQ(one, two);
  EXPECT_EQ(one, kPackHash) << std::hex << "0x" << one;
}

TEST(ExperimentDeterminism, MovingObstacleMapsMatchTheGoldenHashesOnOneAndTwoThreads) {
  const std::uint64_t patrol = sweep_hash("maps/patrol.yaml", 2, 1), rockfall = sweep_hash("maps/rockfall.yaml", 2, 1);
  std::printf("patrol hash 0x%016" PRIx64 ", rockfall hash 0x%016" PRIx64 "\n", patrol, rockfall);
  EXPECT_EQ(sweep_hash("maps/patrol.yaml", 2, 2), patrol);
  EXPECT_EQ(sweep_hash("maps/rockfall.yaml", 2, 2), rockfall);
  EXPECT_EQ(patrol, kPatrolHash) << std::hex << "0x" << patrol;
  EXPECT_EQ(rockfall, kRockfallHash) << std::hex << "0x" << rockfall;
}

TEST(ExperimentDeterminism, LimitedSightMatchesTheGoldenHashOnOneAndTwoThreads) {
  game::GameConfig c = game::preset("peg3d");
  for (game::AgentConfig* a : {&c.pursuer, &c.evader}) a->sensors.sight.enabled = true, a->sensors.sight.fov = 240.0;
  c.pursuer.sensors.sight.estimate = sense::SightEstimate::kDeadReckoning;
  c.pursuer.sensors.sight.share = true;
  const auto both = [&](int threads) {
    Fnv1a h;
    h.add_value(sweep_hash("maps/pack.yaml", 2, threads, c));
    h.add_value(sweep_hash("maps/patrol.yaml", 2, threads, c));
    return h.value();
  };
  const std::uint64_t one = both(1);
  std::printf("sight hash 0x%016" PRIx64 "\n", one);
  EXPECT_EQ(both(2), one);
  EXPECT_EQ(one, kSightHash) << std::hex << "0x" << one;
}

}  // namespace
}  // namespace peg3d::experiment
