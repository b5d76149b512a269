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

TrialResult run_trial(std::shared_ptr<const world::Arena> arena, const TrialSpec& spec, ProgressReporter* progress) {
  assert(spec.scenario != nullptr);
  const auto stream = [&](TrialStream s) { return derive_seed(spec.seed, {static_cast<std::uint64_t>(s)}); };
  TrialResult r;
  r.pursuer = game::make_policy(spec.config.pursuer, game::Role::kPursuer, stream(TrialStream::kPursuer));
  r.evader = game::make_policy(spec.config.evader, game::Role::kEvader, stream(TrialStream::kEvader));
  game::Game game(arena, spec.config);
  r.training.reserve(spec.episodes);
  for (int e = 0; e < spec.episodes; ++e) {
    const auto seed = derive_seed(spec.seed, {static_cast<std::uint64_t>(TrialStream::kTrainingEpisode),
                                              static_cast<std::uint64_t>(e)});
    r.training.push_back(game.play(*spec.scenario, *r.pursuer, *r.evader, /*learning=*/true, seed));
    if (progress) progress->episode_done();
  }
  if (spec.keep_trace) r.trace.reserve(spec.config.max_steps() + 1);
  r.evaluation = game.play(*spec.scenario, *r.pursuer, *r.evader, /*learning=*/false, stream(TrialStream::kEvaluation),
                           spec.keep_trace ? &r.trace : nullptr);
  if (progress) progress->episode_done();
  return r;
}

game::EpisodeResult evaluate(std::shared_ptr<const world::Arena> arena, const game::GameConfig& config,
                             const world::Scenario& scenario, game::Policy& pursuer, game::Policy& evader,
                             std::uint64_t seed, std::vector<game::StepRecord>* trace) {
  game::Game game(std::move(arena), config);
  if (trace) trace->reserve(config.max_steps() + 1);
  return game.play(scenario, pursuer, evader, /*learning=*/false, seed, trace);
}

}  // namespace peg3d::experiment
