#include "players/policy_factory.hpp"

#include "players/facl_policy.hpp"
#include "players/scripted_policies.hpp"
#include "players/search_policies.hpp"

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
    case PolicyKind::kSearch: return std::make_unique<SearchPursuer>();
    case PolicyKind::kHide: return std::make_unique<HideEvader>();
  }
  return nullptr;
}

}  // namespace peg3d::game
