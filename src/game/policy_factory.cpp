#include "game/policy_factory.hpp"

#include "game/facl_policy.hpp"
#include "game/scripted_policies.hpp"

namespace peg3d::game {

std::unique_ptr<Policy> make_policy(const AgentConfig& config, Role role, std::uint64_t seed) {
  switch (config.policy) {
    case PolicyKind::kFacl: return std::make_unique<FaclPolicy>(config, role, seed);
    case PolicyKind::kPurePursuit: return std::make_unique<PurePursuit>();
    case PolicyKind::kProportionalNavigation: return std::make_unique<ProportionalNavigation>(config.pn_gain);
    case PolicyKind::kApollonius: return std::make_unique<ApolloniusInterceptor>();
    case PolicyKind::kFlee: return std::make_unique<FleeLineOfSight>();
    case PolicyKind::kFleeApollonius: return std::make_unique<FleeApollonius>();
    case PolicyKind::kRandom: return std::make_unique<RandomWalk>(config.steering, seed);
  }
  return nullptr;
}

}  // namespace peg3d::game
