#pragma once
// Every kind of policy by its name in the configuration (PolicyKind): the one place that knows all of them, so
// that the base interface (policy.hpp) knows none.

#include <cstdint>
#include <memory>

#include "game/game_config.hpp"
#include "game/policy.hpp"

namespace peg3d::game {

/// Builds the policy named by config.policy for `role`; `seed` feeds any randomness it has.
std::unique_ptr<Policy> make_policy(const AgentConfig& config, Role role, std::uint64_t seed);

}  // namespace peg3d::game
