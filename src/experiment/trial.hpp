#pragma once
// One trial: a pursuer and an evader learn together for a number of episodes from a scenario's start, then
// play one greedy evaluation episode from the same start. Every random stream derives from the trial's seed
// by position, so a trial's result does not depend on which thread runs it or what runs beside it.

#include <cstdint>
#include <memory>
#include <vector>

#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "game/policy.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

class ProgressReporter;

struct TrialSpec {
  const world::Scenario* scenario = nullptr;
  game::GameConfig config;
  std::uint64_t seed = 0;  ///< the trial's root seed
  int episodes = 200;      ///< training episodes, >= 0
  bool keep_trace = false; ///< record every step of the evaluation episode
};

struct TrialResult {
  game::EpisodeResult evaluation;            ///< the greedy episode after training
  std::vector<game::EpisodeResult> training; ///< one per training episode (the learning curve)
  std::vector<game::StepRecord> trace;       ///< the evaluation's steps when keep_trace
  std::unique_ptr<game::Policy> pursuer;     ///< the trained policies
  std::unique_ptr<game::Policy> evader;

  int train_captures() const;
};

/// Seeds of a trial's streams, derived from its root seed.
enum class TrialStream : std::uint64_t { kPursuer = 1, kEvader = 2, kTrainingEpisode = 3, kEvaluation = 4 };

/// Trains and evaluates. `progress` (optional) is told of every episode.
TrialResult run_trial(std::shared_ptr<const world::Arena> arena, const TrialSpec& spec,
                      ProgressReporter* progress = nullptr);

/// Plays one greedy evaluation episode of already-built policies.
game::EpisodeResult evaluate(std::shared_ptr<const world::Arena> arena, const game::GameConfig& config,
                             const world::Scenario& scenario, game::Policy& pursuer, game::Policy& evader,
                             std::uint64_t seed, std::vector<game::StepRecord>* trace = nullptr);

}  // namespace peg3d::experiment
