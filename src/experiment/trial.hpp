#pragma once
// One trial: the agents of a scenario learn together for a number of episodes from its start, then play one
// greedy evaluation episode from the same start. Every random stream derives from the trial's seed by
// position, so a trial's result does not depend on which thread runs it or what runs beside it.

#include <cstdint>
#include <vector>

#include "experiment/training.hpp"
#include "game/episode.hpp"
#include "players/lineup.hpp"
#include "game/sim.hpp"
#include "sweep/parallel_runner.hpp"

namespace peg3d::experiment {

struct TrialSpec {
  const world::Scenario* scenario = nullptr;
  std::uint64_t seed = 0;   ///< the trial's root seed
  int episodes = 200;       ///< training episodes, >= 0
  bool keep_trace = false;  ///< record every step of the evaluation episode
  sweep::StopCheck stop{};  ///< polled before every episode; a stop request throws RunCancelled
  TrainingConfig training{};  ///< how the learners train (co-learning by default)
  /// The classic opponents mixed into training (experiment/opponent_pool.hpp); null or empty: co-learning only.
  const OpponentPool* pool = nullptr;
  sweep::ProgressReporter* progress = nullptr;  ///< told of every episode; null: none
};

struct TrialResult {
  game::EpisodeResult evaluation;  ///< the greedy episode after training
  TrainingResult training;         ///< the training episodes (the learning curve) and their opponents
  game::Trace trace;               ///< the evaluation's steps when keep_trace
  players::RoleModels pursuer_models;  ///< the trained FACL models of each role (empty when none learns)
  players::RoleModels evader_models;

  int train_captures() const;
};

/// Trains and evaluates the agents the Sim's configuration names: co-learning, with spec.pool's classic
/// opponents mixed in when given (its Sims must share the arena of `sim`). Throws RunCancelled when spec.stop
/// asks to stop (checked between episodes, so a run gives up within one episode's time).
TrialResult run_trial(const game::Sim& sim, const TrialSpec& spec);

/// Plays one greedy evaluation episode of already-built policies, in a state of the caller's (reused across
/// calls to spare building its collision world).
game::EpisodeResult evaluate(const game::Sim& sim, game::SimState& state, const world::Scenario& scenario,
                             const players::Lineup& lineup, std::uint64_t seed, game::Trace* trace = nullptr);

}  // namespace peg3d::experiment
