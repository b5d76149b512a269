#pragma once
// Trained FACL policies as versioned JSON documents: the agent's configuration (which fixes the rule bases)
// and every learner's actor and critic consequents. Doubles are written with round-trip precision, so a
// loaded policy acts exactly as the saved one.
//
//   {"format": "peg3d-policy", "version": 1, "role": "pursuer", "config": {...AgentConfig...},
//    "channels": [{"rules": 625, "actions": 1, "actor": [...], "critic": [...]}, ...]}

#include <memory>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "game/facl_policy.hpp"

namespace peg3d::game {

inline constexpr const char* kPolicyFormat = "peg3d-policy";
inline constexpr int kPolicyVersion = 1;

/// A policy document that cannot be read; what() says why (and the caller adds the file name).
class PolicyFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

nlohmann::json policy_to_json(const FaclPolicy& policy);

/// Rebuilds a policy from its document; `seed` seeds its exploration noise should it keep learning.
/// Throws PolicyFormatError on a wrong format, an unsupported version or tables that do not fit.
std::unique_ptr<FaclPolicy> policy_from_json(const nlohmann::json& document, std::uint64_t seed = 0);

}  // namespace peg3d::game
