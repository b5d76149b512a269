// peg-bench-game: cost of the learning loop's parts and of whole training steps on maps/paper.yaml.
//   BM_FireSparse / BM_FireDense     firing the paper's 625-rule base (16 rules visited vs all 625)
//   BM_FaclActLearn/<structure>      one agent's act + TD update (0: paper joint 4-input, 1: peg3d per-angle)
//   BM_TrainingSteps/<preset>        full co-learning steps of both agents (items/s = game steps per second
//                                    on one core): 0 peg3d, 1 paper, 2 baseline
//   BM_TeamTrainingSteps             the same for the 3 v 2 scenario of maps/pack.yaml (peg3d preset)
// Run: build/bin/peg-bench-game [--benchmark_filter=...]

#include <memory>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "cli_common.hpp"
#include "core/random.hpp"
#include "fuzzy/rule_base.hpp"
#include "game/episode.hpp"
#include "players/facl_policy.hpp"
#include "players/lineup.hpp"
#include "world/arena.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"

namespace {

using namespace peg3d;

fuzzy::RuleBase paper_rule_base() {
  return fuzzy::RuleBase({fuzzy::TriangularPartition(0, 35, 5), fuzzy::TriangularPartition(-kPi, kPi, 5),
                          fuzzy::TriangularPartition(0, 35, 5), fuzzy::TriangularPartition(-kPi, kPi, 5)});
}

std::vector<std::array<double, 4>> random_inputs(std::size_t n) {
  Rng rng(1);
  std::uniform_real_distribution<double> d(0, 35), a(-kPi, kPi);
  std::vector<std::array<double, 4>> x(n);
  for (auto& v : x) v = {d(rng), a(rng), d(rng), a(rng)};
  return x;
}

void BM_FireSparse(benchmark::State& state) {
  const fuzzy::RuleBase rb = paper_rule_base();
  const auto xs = random_inputs(1024);
  fuzzy::FiredRules f;
  std::size_t i = 0;
  for (auto _ : state) {
    rb.fire(xs[i++ & 1023], f);
    benchmark::DoNotOptimize(f.strength[0]);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FireSparse);

void BM_FireDense(benchmark::State& state) {
  const fuzzy::RuleBase rb = paper_rule_base();
  const auto xs = random_inputs(1024);
  std::vector<double> phi(rb.rules());
  std::size_t i = 0;
  for (auto _ : state) {
    rb.fire_dense(xs[i++ & 1023], phi);
    benchmark::DoNotOptimize(phi[0]);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FireDense);

void BM_FaclActLearn(benchmark::State& state) {
  const game::AgentConfig c = game::agent_preset(state.range(0) == 0 ? "paper" : "peg3d", game::Role::kPursuer);
  players::FaclPolicy p(c, game::Role::kPursuer, 1);
  Rng rng(2);
  std::uniform_real_distribution<double> d(0, 35), a(-kPi, kPi);
  std::vector<game::AgentView> views(1024);
  for (auto& v : views) {
    v.percept.target_distance = d(rng);
    v.percept.target = {a(rng), a(rng)};
    v.percept.obstacle = {d(rng) / 7, Vec3::Zero(), true};
    v.percept.to_obstacle = {a(rng), a(rng)};
  }
  p.begin_episode(views[0], true);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.act(views[i & 1023]));
    p.learn(0.5, views[(i + 1) & 1023], false);
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FaclActLearn)->Arg(0)->Arg(1);

// Training episodes of the scenarios of `map` in turn, as a trial plays them; items are game steps.
void training_steps(benchmark::State& state, const char* map, const char* preset, int only_scenario) {
  const auto arena = world::Arena::build(world::load_map(cli::data_dir() / map));
  const game::GameConfig config = game::preset(preset);
  const game::Sim sim(arena, config);
  game::SimState st(sim);
  const auto& scenarios = arena->map().scenarios;
  long long steps = 0, agent_steps = 0;
  std::uint64_t episode = 0;
  // One set of learners plays every scenario in turn (they all have the first scenario's team sizes).
  const world::Scenario& first = scenarios[std::size_t(std::max(only_scenario, 0))];
  players::Lineup lineup;
  players::add_configured(lineup, config, game::Role::kPursuer, int(first.pursuers.size()), 1);
  players::add_configured(lineup, config, game::Role::kEvader, int(first.evaders.size()), 2);
  for (auto _ : state) {
    const std::size_t k = only_scenario >= 0 ? std::size_t(only_scenario) : episode % scenarios.size();
    const long long before = steps;
    steps += game::play(sim, st, scenarios[k], lineup.policies(), true, derive_seed(3, {episode++})).steps;
    agent_steps += (steps - before) * scenarios[k].agents();
  }
  state.SetItemsProcessed(steps);
  state.counters["steps_per_episode"] = static_cast<double>(steps) / static_cast<double>(state.iterations());
  state.counters["agent_steps_per_s"] = benchmark::Counter(static_cast<double>(agent_steps), benchmark::Counter::kIsRate);
}

void BM_TrainingSteps(benchmark::State& state) {
  training_steps(state, "maps/paper.yaml", game::kPresetNames[state.range(0)], -1);
}
BENCHMARK(BM_TrainingSteps)->DenseRange(0, std::size(game::kPresetNames) - 1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_TeamTrainingSteps(benchmark::State& state) { training_steps(state, "maps/pack.yaml", "peg3d", 0); }
BENCHMARK(BM_TeamTrainingSteps)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
