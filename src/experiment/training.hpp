#pragma once
// How FACL agents are trained (docs/learning.md). The paper's procedure is co-learning: the pursuers and the
// evaders of a scenario learn together, each against the other, for every training episode. The opponent
// pool mixes in episodes where one FACL role learns against a classic opponent (a guidance law or a scripted
// evader), so that what it learns holds against opponents it did not grow up with. Which episode plays which
// opponent derives from the trial's seed, so a trial stays a pure function of its seed.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "players/lineup.hpp"
#include "game/sim.hpp"
#include "sweep/parallel_runner.hpp"
#include "world/arena.hpp"

namespace peg3d::sweep {
class ProgressReporter;
}

namespace peg3d::experiment {

/// Seeds of a trial's streams, derived from its root seed.
enum class TrialStream : std::uint64_t {
  kPursuer = 1,
  kEvader = 2,
  kTrainingEpisode = 3,
  kEvaluation = 4,
  kTrainingOpponent = 5,  ///< per episode: which opponent it plays (opponent pool)
  kPoolOpponents = 6,     ///< the pool's classic policies (per entry)
  kTrainingStart = 7,     ///< per episode: whether it starts at random places, and where (random starts)
};
std::uint64_t stream_seed(std::uint64_t trial_seed, TrialStream s);

class OpponentPool;

/// What a training plays besides the learners themselves.
struct TrainingContext {
  const game::Sim* sim = nullptr;  ///< the game the lineup learns in; its configuration's `training` settings apply
  /// The classic opponents mixed in (its Sims share the arena of `sim`); null or empty: co-learning only.
  const OpponentPool* pool = nullptr;
  std::span<const world::Scenario> scenarios{};///< episode e starts from scenarios[e % size], >= 1 of them
  int pursuers = 0;                            ///< the lineup's first `pursuers` policies are pursuers, the rest evaders
  std::uint64_t seed = 0;                      ///< the trial's root seed; every stream derives from it (TrialStream)
  int episodes = 0;                            ///< learning episodes, >= 0
  sweep::StopCheck stop{};                     ///< polled before every episode; true throws RunCancelled
  sweep::ProgressReporter* progress = nullptr;  ///< told of every episode; null: none
};

/// What a training did, episode by episode.
struct TrainingResult {
  std::vector<game::EpisodeResult> episodes;  ///< one per training episode, in order (the learning curve)
  std::vector<int> opponents;                 ///< per episode: its opponent-pool entry, -1 for co-learning
};

/// Plays context.episodes learning episodes with `lineup` (at least as many policies of each role as any
/// scenario has agents; a smaller scenario plays the first ones), in `state` (scratch, reused). Episode e
/// starts from scenarios[e % size] (or, with training.random_starts, from a random_start() of its agents)
/// and, with a pool, plays the opponent pool->choose() draws for it (co-learning for -1). A role past its
/// training.*_learning share of the episodes plays greedily without learning. Every stream derives from
/// context.seed as TrialStream says. Throws RunCancelled when context.stop asks, std::logic_error when the
/// configuration trains with an opponent pool and none is given.
TrainingResult train_lineup(const TrainingContext& context, game::Lineup& lineup, game::SimState& state);

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
  /// episode: a pool episode with probability pool_share, its entry uniform over the pool's entries whose
  /// learner still learns (training.pursuer_learning, evader_learning); -1 when none does.
  int choose(std::uint64_t seed, bool pursuers_learn = true, bool evaders_learn = true) const;

 private:
  game::TrainingConfig training_;
  std::vector<Entry> entries_;
};

/// The policy name of each training episode's opponent-pool opponent, "" for a co-learning episode (-1), as
/// learning_curves.csv writes them. Throws std::logic_error for an entry that is neither.
std::vector<std::string> pool_opponent_names(const OpponentPool& pool, std::span<const int> opponents);

/// Checks a run's opponents read back from a journal: one per training episode, each -1 or an entry of `pool`.
/// Throws InputError (field training_opponent) otherwise.
void check_journaled_opponents(const OpponentPool& pool, std::span<const int> opponents, std::size_t episodes);

}  // namespace peg3d::experiment
