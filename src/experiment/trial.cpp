#include "experiment/trial.hpp"

#include <cassert>

#include "core/random.hpp"
#include "experiment/progress_reporter.hpp"

namespace peg3d::experiment {

int TrialResult::train_captures() const {
  int n = 0;
  for (const auto& e : training) n += e.captured();
  return n;
}

TrialResult run_trial(const game::Sim& sim, const TrialSpec& spec, ProgressReporter* progress) {
  assert(spec.scenario != nullptr);
  const world::Scenario& scenario = *spec.scenario;
  TrialResult r;
  game::Lineup lineup;
  game::add_configured(lineup, sim.config(), game::Role::kPursuer, static_cast<int>(scenario.pursuers.size()),
                       stream_seed(spec.seed, TrialStream::kPursuer), &r.pursuer_models);
  game::add_configured(lineup, sim.config(), game::Role::kEvader, static_cast<int>(scenario.evaders.size()),
                       stream_seed(spec.seed, TrialStream::kEvader), &r.evader_models);
  game::SimState state(sim);
  train_lineup(sim, spec.pool, lineup, static_cast<int>(scenario.pursuers.size()), {&scenario, 1}, spec.seed,
               spec.episodes, spec.stop, progress, state, r.training, r.training_opponent);
  throw_if_stopped(spec.stop);
  if (spec.keep_trace) r.trace.reserve(sim.max_steps(), scenario.agents());
  r.evaluation = game::play(sim, state, scenario, lineup.policies(), /*learning=*/false,
                            stream_seed(spec.seed, TrialStream::kEvaluation), spec.keep_trace ? &r.trace : nullptr);
  if (progress) progress->episode_done();
  return r;
}

game::EpisodeResult evaluate(const game::Sim& sim, game::SimState& state, const world::Scenario& scenario,
                             const game::Lineup& lineup, std::uint64_t seed, game::Trace* trace) {
  if (trace) trace->reserve(sim.max_steps(), scenario.agents());
  return game::play(sim, state, scenario, lineup.policies(), /*learning=*/false, seed, trace);
}

}  // namespace peg3d::experiment
