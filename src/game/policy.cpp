#include "game/policy.hpp"

#include <stdexcept>

#include "game/facl_policy.hpp"
#include "game/scripted_policies.hpp"

namespace peg3d::game {

std::unique_ptr<Policy> make_policy(const AgentConfig& config, Role role, std::uint64_t seed) {
  const std::string& p = config.policy;
  if (p == "facl") return std::make_unique<FaclPolicy>(config, role, seed);
  if (p == "pure-pursuit") return std::make_unique<PurePursuit>();
  if (p == "pn") return std::make_unique<ProportionalNavigation>(config.pn_gain);
  if (p == "apollonius") return std::make_unique<ApolloniusInterceptor>();
  if (p == "flee") return std::make_unique<FleeLineOfSight>();
  if (p == "flee-apollonius") return std::make_unique<FleeApollonius>();
  if (p == "random") return std::make_unique<RandomWalk>(config.steering, seed);
  throw std::invalid_argument("unknown policy '" + p + "'");
}

}  // namespace peg3d::game
