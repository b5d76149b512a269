#include "experiment/trial.hpp"

#include <cassert>
#include <memory>
#include <stdexcept>

#include "core/random.hpp"
#include "experiment/progress_reporter.hpp"

namespace peg3d::experiment {

int TrialResult::train_captures() const {
  int n = 0;
  for (const auto& e : training) n += e.captured();
  return n;
}

std::uint64_t stream_seed(std::uint64_t trial_seed, TrialStream s) {
  return derive_seed(trial_seed, {static_cast<std::uint64_t>(s)});
}

TrialResult run_trial(const game::Sim& sim, const TrialSpec& spec, ProgressReporter* progress) {
  assert(spec.scenario != nullptr);
  if (sim.config().training.procedure != game::TrainingProcedure::kCoLearning && spec.pool == nullptr) {
    throw std::logic_error("run_trial: the configuration trains with an opponent pool, but the trial was given none");
  }
  const world::Scenario& scenario = *spec.scenario;
  TrialResult r;
  game::Lineup lineup;
  game::add_configured(lineup, sim.config(), game::Role::kPursuer, static_cast<int>(scenario.pursuers.size()),
                       stream_seed(spec.seed, TrialStream::kPursuer), &r.pursuer_models);
  game::add_configured(lineup, sim.config(), game::Role::kEvader, static_cast<int>(scenario.evaders.size()),
                       stream_seed(spec.seed, TrialStream::kEvader), &r.evader_models);
  game::SimState state(sim);
  r.training.reserve(static_cast<std::size_t>(spec.episodes));
  r.training_opponent.reserve(static_cast<std::size_t>(spec.episodes));
  // Pool episodes: the learning role's FACL policies (the same objects, so learning carries on) beside the
  // pool entry's classic policies, built on first use.
  const int pursuers = static_cast<int>(scenario.pursuers.size()), evaders = static_cast<int>(scenario.evaders.size());
  const auto entries = spec.pool != nullptr ? spec.pool->entries() : std::span<const OpponentPool::Entry>{};
  std::vector<std::unique_ptr<game::Lineup>> opponents(entries.size());
  std::vector<game::Policy*> mixed(std::size_t(pursuers + evaders));
  for (int e = 0; e < spec.episodes; ++e) {
    throw_if_stopped(spec.stop);
    const auto seed = derive_seed(spec.seed, {static_cast<std::uint64_t>(TrialStream::kTrainingEpisode),
                                              static_cast<std::uint64_t>(e)});
    const int k = entries.empty() ? -1
                                  : spec.pool->choose(derive_seed(spec.seed, {static_cast<std::uint64_t>(TrialStream::kTrainingOpponent),
                                                                              static_cast<std::uint64_t>(e)}));
    if (k < 0) {
      r.training.push_back(game::play(sim, state, scenario, lineup.policies(), /*learning=*/true, seed));
    } else {
      const OpponentPool::Entry& entry = entries[std::size_t(k)];
      const game::Role other = entry.learner == game::Role::kPursuer ? game::Role::kEvader : game::Role::kPursuer;
      auto& opponent = opponents[std::size_t(k)];
      if (!opponent) {
        opponent = std::make_unique<game::Lineup>();
        game::add_configured(*opponent, entry.sim.config(), other, other == game::Role::kPursuer ? pursuers : evaders,
                             derive_seed(spec.seed, {static_cast<std::uint64_t>(TrialStream::kPoolOpponents),
                                                     static_cast<std::uint64_t>(k)}));
      }
      for (int i = 0; i < pursuers + evaders; ++i) {
        const bool pursuer = i < pursuers;
        const bool learner_side = pursuer == (entry.learner == game::Role::kPursuer);
        mixed[std::size_t(i)] = learner_side ? &lineup[i] : &(*opponent)[pursuer ? i : i - pursuers];
      }
      r.training.push_back(game::play(entry.sim, state, scenario, mixed, /*learning=*/true, seed));
    }
    r.training_opponent.push_back(k);
    if (progress) progress->episode_done();
  }
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
