#pragma once
// Every player peg3d ships, in one table (the players' registry): its name, which is what configurations
// (`pursuer.policy`), flags (`--pursuers`, `--evaders`), the Python batch's `opponents`, results and help texts
// call it; the roles it plays; what it needs; one line of help; and its factory. Programs list, check and build
// players through this table only: no other list of player names exists. A policy file (players/saved_policy.hpp)
// is not a player of the table but a saved model that plays like one.
//
// Adding a player: its class in players/, one row in registry.cpp (docs/architecture.md, "Adding a player").

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "game/game_config.hpp"
#include "game/policy.hpp"

namespace peg3d::players {

/// The learner of the paper: its name, where code means FACL itself (its policy files, its training).
inline constexpr std::string_view kFacl = "facl";

/// Roles as a set.
enum RoleSet : unsigned { kPursuers = 1u << 0, kEvaders = 1u << 1, kBothRoles = kPursuers | kEvaders };
constexpr RoleSet role_set(game::Role role) { return role == game::Role::kPursuer ? kPursuers : kEvaders; }

/// What a player needs of the game to play as it is meant to.
enum Need : unsigned {
  kNeedsNothing = 0,
  /// It learns (FACL): the experiments train it; as a fixed opponent it plays a saved policy file.
  kNeedsTraining = 1u << 0,
  /// It is made for the partial game, limited sight (docs/sight.md); with full information it plays as a
  /// classic player does (search as pure pursuit, hide as flee).
  kNeedsSight = 1u << 1,
};

struct PlayerInfo {
  std::string_view name;  ///< a word (config::is_name)
  unsigned roles = 0;     ///< RoleSet: the roles it plays
  /// RoleSet: the roles in whose default line-ups it plays, the classic baselines of the full-information game
  /// (peg-matchup's and peg-league's defaults, the opponent pool's).
  unsigned baseline = 0;
  unsigned needs = kNeedsNothing;  ///< Need flags
  std::string_view help;           ///< one line: what it does
  /// A new player for an agent of `role` with `config` (its settings: pn_gain, FACL's tables and rates, the
  /// steering bound); `seed` feeds any randomness it has.
  std::unique_ptr<game::Policy> (*make)(const game::AgentConfig& config, game::Role role, std::uint64_t seed);

  bool plays(game::Role role) const { return (roles & role_set(role)) != 0; }
  bool learns() const { return (needs & kNeedsTraining) != 0; }
};

/// The table, in the order listings show it.
std::span<const PlayerInfo> registry();
/// The player called `name`; null when none is.
const PlayerInfo* find_player(std::string_view name);
/// The player called `name` that plays `role`; throws InvalidParameter naming `field`, with the players of the
/// role, for an unknown name or one that does not play the role.
const PlayerInfo& player_named(std::string_view name, game::Role role, const std::string& field);
/// The names of the players of `role`, "a, b, c", for help texts and messages; `excluding` leaves out the players
/// with any of those Need flags.
std::string player_names(game::Role role, unsigned excluding = 0);
/// The default line-up of `role`: its baseline players, in the table's order.
std::vector<std::string> baseline_players(game::Role role);
/// The table as text, a player a line: name, roles, needs, help (--list-players).
std::string player_listing();

/// A new player of config.policy for an agent of `role` (player_named, field "policy").
std::unique_ptr<game::Policy> make_player(const game::AgentConfig& config, game::Role role, std::uint64_t seed);
/// Whether config.policy names a learning player (FACL).
bool learns(const game::AgentConfig& config);

/// Checks every agent's policy of a configuration against the table: throws InvalidParameter naming the field
/// ("pursuer.policy", "evaders.1.policy") for a name that is no player, or a player of the other role.
void check_players(const game::GameConfig& config);

}  // namespace peg3d::players
