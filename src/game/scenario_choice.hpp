#pragma once
// Which of a map's scenarios a run of several games plays (a batch, a FACL best response), and how many agents
// of a role those scenarios start: one team size per run, since the games share their agents' line-up.

#include <string>
#include <vector>

#include "game/role.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::game {

/// Indices into map.scenarios of those `names` names, in their order, or of every scenario with the first one's
/// numbers of pursuers and evaders when `names` is empty. Throws InvalidParameter naming `field` for a map
/// without scenarios, a name the map lacks, or a named scenario whose team sizes differ from the first named.
std::vector<int> scenarios_of_one_team_size(const world::MapSpec& map, const std::vector<std::string>& names,
                                            const std::string& field);

/// The most agents of `role` any of the map's scenarios starts (what a player of that role must fit).
int most_agents(const world::MapSpec& map, Role role);

}  // namespace peg3d::game
