#include "experiment/trial.hpp"

#include <cassert>

#include "core/random.hpp"
#include "sweep/progress_reporter.hpp"

namespace peg3d::experiment {

int TrialResult::train_captures() const {
  int n = 0;
  for (const auto& e : training.episodes) n += e.captured();
  return n;
}

TrialResult run_trial(const game::Sim& sim, const TrialSpec& spec) {
  assert(spec.scenario != nullptr);
  const world::Scenario& scenario = *spec.scenario;
  TrialResult r;
  players::Lineup lineup;
  const int pursuers = static_cast<int>(scenario.pursuers.size());
  players::add_configured(lineup, sim.config(), game::Role::kPursuer, pursuers,
                       stream_seed(spec.seed, TrialStream::kPursuer), &r.pursuer_models);
  players::add_configured(lineup, sim.config(), game::Role::kEvader, static_cast<int>(scenario.evaders.size()),
                       stream_seed(spec.seed, TrialStream::kEvader), &r.evader_models);
  game::SimState state(sim);
  r.training = train_lineup({.sim = &sim,
                             .training = spec.training,
                             .pool = spec.pool,
                             .scenarios = {&scenario, 1},
                             .pursuers = pursuers,
                             .seed = spec.seed,
                             .episodes = spec.episodes,
                             .stop = spec.stop,
                             .progress = spec.progress},
                            lineup, state);
  sweep::throw_if_stopped(spec.stop);
  if (spec.keep_trace) r.trace.reserve(sim.max_steps(), scenario.agents());
  r.evaluation = game::play(sim, state, scenario, lineup.policies(), /*learning=*/false,
                            stream_seed(spec.seed, TrialStream::kEvaluation), spec.keep_trace ? &r.trace : nullptr);
  if (spec.progress) spec.progress->episode_done();
  return r;
}

game::EpisodeResult evaluate(const game::Sim& sim, game::SimState& state, const world::Scenario& scenario,
                             const players::Lineup& lineup, std::uint64_t seed, game::Trace* trace) {
  if (trace) trace->reserve(sim.max_steps(), scenario.agents());
  return game::play(sim, state, scenario, lineup.policies(), /*learning=*/false, seed, trace);
}

}  // namespace peg3d::experiment
