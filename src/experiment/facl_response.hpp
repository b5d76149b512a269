#pragma once
// A FACL best response (issue 52, peg3d.selfplay): the FACL agents of one role learn against a fixed opponent, a
// classic player, a policy file or a mixture of them drawn per episode (players/saved_policy.hpp). The opponent
// plays as it would in an evaluation, greedily and learning nothing; the learners of the role share their models as
// add_configured makes them (a team of equal settings learns one model). The result is a pure function of the Sim,
// the opponent and the settings.

#include <cstdint>
#include <string>
#include <vector>

#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "players/lineup.hpp"
#include "players/saved_policy.hpp"

namespace peg3d::experiment {

struct FaclResponseSettings {
  int episodes = 4000;  ///< training episodes, in [1, 10^7]
  /// The map's scenarios the episodes start from, by name, taking turns (episode e plays the (e mod count)-th); they
  /// must have the same numbers of pursuers and evaders. Empty: the map's scenarios with the first one's numbers.
  std::vector<std::string> scenarios;
  std::uint64_t seed = 0;  ///< root seed: the learners' exploration and every episode's start
};

/// `config` with the agents of `role` (the first `count`) under `opponent`'s own configuration when it carries one
/// (a FACL file's, or a mixture's FACL members'), as a batch plays them: a Sim for train_facl_response is made from it.
game::GameConfig with_opponent_config(game::GameConfig config, game::Role role, int count,
                                      const players::SavedPolicy& opponent);

/// Trains the agents of `role` in `sim` against `opponent`, played by every agent of the other role. The Sim's
/// configuration gives the learners' settings: every agent of `role` must play facl. Returns their models (agent
/// k's is models.for_agent(k)). Throws InvalidParameter naming the setting at fault (episodes, scenarios, policy).
players::RoleModels train_facl_response(const game::Sim& sim, game::Role role, const players::SavedPolicy& opponent,
                                        const FaclResponseSettings& settings);

}  // namespace peg3d::experiment
