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

#include "core/config_fields.hpp"
#include "experiment/opponent_pool.hpp"
#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "players/lineup.hpp"
#include "sweep/parallel_runner.hpp"
#include "world/arena.hpp"

namespace peg3d::sweep {
class ProgressReporter;
}

namespace peg3d::experiment {

/// How the FACL agents of a trial train (docs/learning.md). The defaults are the paper's procedure.
enum class TrainingProcedure {
  kCoLearning,    ///< the paper: every episode, the FACL pursuers and evaders learn against each other
  kOpponentPool,  ///< a share of the episodes, one FACL role learns against a classic opponent of the pool
};
inline constexpr config::EnumNames<TrainingProcedure, 2> kTrainingProcedureNames{
    {{TrainingProcedure::kCoLearning, "co-learning"}, {TrainingProcedure::kOpponentPool, "opponent-pool"}}};

struct TrainingConfig {
  TrainingProcedure procedure = TrainingProcedure::kCoLearning;
  OpponentPoolConfig pool;  ///< the classic opponents of opponent-pool training (experiment/opponent_pool.hpp)
  /// Share of training episodes, in [0, 1], whose agents start at random places in the arena (game/random_start.hpp)
  /// instead of the scenario's; the scenario still gives how many agents play.
  double random_starts = 0.0;
  double random_start_gap = 20.0;  ///< m, >= 0: least distance from a pursuer to an evader at a random start
  /// Share of the training episodes, in (0, 1], in which the pursuers learn: the first ones. Afterwards they
  /// play their policy greedily without learning, and the opponent pool leaves out their entries.
  double pursuer_learning = 1.0;
  double evader_learning = 1.0;  ///< likewise for the evaders
  bool operator==(const TrainingConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, TrainingConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.choice("procedure", c.procedure, kTrainingProcedureNames,
           "co-learning (the paper) or opponent-pool (co-learning mixed with episodes against classic opponents)");
  v.section("pool", c.pool, "opponent-pool: the classic opponents and how often they play");
  v.number("random_starts", c.random_starts, Range::closed(0, 1), "",
           "share of training episodes that start at random places in the arena instead of the scenario's");
  v.number("random_start_gap", c.random_start_gap, Range::non_negative(), "m",
           "least distance from a pursuer to an evader at a random start");
  v.number("pursuer_learning", c.pursuer_learning, Range::open_closed(0, 1), "",
           "share of the training episodes (the first ones) in which the pursuers learn");
  v.number("evader_learning", c.evader_learning, Range::open_closed(0, 1), "",
           "share of the training episodes (the first ones) in which the evaders learn");
  v.require(c.procedure != TrainingProcedure::kOpponentPool || !c.pool.pursuers.empty() || !c.pool.evaders.empty(),
            "procedure", "opponent-pool", "needs at least one player in pool.pursuers or pool.evaders");
}

/// The opponent pool of `training` for a game configured by `config` (empty for co-learning).
OpponentPool make_pool(const std::shared_ptr<const world::Arena>& arena, const game::GameConfig& config,
                       const TrainingConfig& training);

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
  const game::Sim* sim = nullptr;  ///< the game the lineup learns in
  TrainingConfig training{};       ///< how it learns
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
/// starts from scenarios[e % size] (or, with context.training.random_starts, from a random_start() of its
/// agents) and, with a pool, plays the opponent pool->choose() draws for it (co-learning for -1). A role past its
/// context.training.*_learning share of the episodes plays greedily without learning. Every stream derives from
/// context.seed as TrialStream says. Throws RunCancelled when context.stop asks, std::logic_error when the
/// training is by opponent pool and none is given.
TrainingResult train_lineup(const TrainingContext& context, players::Lineup& lineup, game::SimState& state);

}  // namespace peg3d::experiment
