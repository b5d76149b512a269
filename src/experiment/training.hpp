#pragma once
// How FACL agents are trained (docs/learning.md). The paper's procedure is co-learning: the pursuers and the
// evaders of a scenario learn together, each against the other, for every training episode. The opponent
// pool mixes in episodes where one FACL role learns against a classic opponent (a guidance law or a scripted
// evader), so that what it learns holds against opponents it did not grow up with. Which episode plays which
// opponent derives from the trial's seed, so a trial stays a pure function of its seed.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

/// The classic opponents of an opponent-pool training, each with the Sim it is played in (the game
/// configuration with every agent of the opponent's role playing it). Built once per sweep, before any run,
/// and shared read-only by every trial and thread.
class OpponentPool {
 public:
  struct Entry {
    game::Role learner;         ///< the FACL role that learns in these episodes
    game::PolicyKind opponent;  ///< what every agent of the other role plays
    game::Sim sim;
  };

  /// The pool of config.training for a game configured by `config`: the chosen classic policies of each role
  /// whose agents are FACL learners. Empty for co-learning. Throws like Sim's constructor.
  OpponentPool(const std::shared_ptr<const world::Arena>& arena, const game::GameConfig& config);

  const game::TrainingConfig& config() const { return training_; }
  std::span<const Entry> entries() const { return entries_; }
  bool empty() const { return entries_.empty(); }

  /// The entry a training episode plays, drawn from `seed` (the episode's own), or -1 for a co-learning
  /// episode: a pool episode with probability pool_share, its entry uniform over the pool.
  int choose(std::uint64_t seed) const;

 private:
  game::TrainingConfig training_;
  std::vector<Entry> entries_;
};

}  // namespace peg3d::experiment
