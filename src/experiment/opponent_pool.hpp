#pragma once
// The opponent pool (docs/learning.md): classic players that FACL learners meet in a share of their training
// episodes, so that what they learn holds against opponents they did not grow up with. Its settings name the
// players by their names in the players' registry (players/registry.hpp).

#include <concepts>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "core/config_fields.hpp"
#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "players/registry.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

struct OpponentPoolConfig {
  /// The share of training episodes, in [0, 1], in which one FACL role (drawn uniformly with the opponent) plays
  /// a classic opponent instead of its co-learning partner.
  double share = 0.5;
  /// The classic pursuers the FACL evaders meet, by name (classic players of the role: no learner); by default
  /// the pursuers' baselines.
  std::vector<std::string> pursuers = players::baseline_players(game::Role::kPursuer);
  /// The scripted evaders the FACL pursuers meet; by default the evaders' baselines.
  std::vector<std::string> evaders = players::baseline_players(game::Role::kEvader);
  bool operator==(const OpponentPoolConfig&) const = default;
};

namespace detail {
/// Whether `names` are classic players of `role` (known, of the role, not learners); the first that is not, or -1.
int first_unfit_player(const std::vector<std::string>& names, game::Role role);
}  // namespace detail

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, OpponentPoolConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.number("share", c.share, Range::closed(0, 1), "",
           "share of training episodes in which one FACL role plays a classic opponent of the pool");
  v.names("pursuers", c.pursuers, "classic pursuers (--list-players)", "the classic pursuers the FACL evaders train against");
  v.names("evaders", c.evaders, "scripted evaders (--list-players)", "the scripted evaders the FACL pursuers train against");
  for (const auto& [key, names, role] : {std::tuple{"pursuers", &c.pursuers, game::Role::kPursuer},
                                         std::tuple{"evaders", &c.evaders, game::Role::kEvader}}) {
    const int k = detail::first_unfit_player(*names, role);
    if (k >= 0) {
      v.require(false, std::string(key) + "." + std::to_string(k), (*names)[std::size_t(k)],
                role == game::Role::kPursuer ? "is not a classic pursuer (--list-players)"
                                             : "is not a scripted evader (--list-players)");
    }
  }
}

/// The classic opponents of an opponent-pool training, each with the Sim it is played in (the game
/// configuration with every agent of the opponent's role playing it). Built once per sweep, before any run,
/// and shared read-only by every trial and thread.
class OpponentPool {
 public:
  struct Entry {
    game::Role learner;    ///< the FACL role that learns in these episodes
    std::string opponent;  ///< the player every agent of the other role plays
    game::Sim sim;
  };

  /// The pool of `pool` for a game configured by `config`: the pool's players of each role whose agents are FACL
  /// learners (the evaders' first). Empty when `enabled` is false (co-learning). Throws like Sim's constructor.
  OpponentPool(const std::shared_ptr<const world::Arena>& arena, const game::GameConfig& config,
               const OpponentPoolConfig& pool, bool enabled);

  std::span<const Entry> entries() const { return entries_; }
  bool empty() const { return entries_.empty(); }

  /// The entry a training episode plays, drawn from `seed` (the episode's own), or -1 for a co-learning
  /// episode: a pool episode with probability `share`, its entry uniform over the pool's entries whose learner
  /// still learns (training.pursuer_learning, evader_learning); -1 when none does.
  int choose(std::uint64_t seed, bool pursuers_learn = true, bool evaders_learn = true) const;

 private:
  double share_ = 0.0;
  std::vector<Entry> entries_;
};

/// The player name of each training episode's opponent-pool opponent, "" for a co-learning episode (-1), as
/// learning_curves.csv writes them. Throws std::logic_error for an entry that is neither.
std::vector<std::string> pool_opponent_names(const OpponentPool& pool, std::span<const int> opponents);

/// Checks a run's opponents read back from a journal: one per training episode, each -1 or an entry of `pool`.
/// Throws InputError (field training_opponent) otherwise.
void check_journaled_opponents(const OpponentPool& pool, std::span<const int> opponents, std::size_t episodes);

}  // namespace peg3d::experiment
