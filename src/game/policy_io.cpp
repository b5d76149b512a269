#include "game/policy_io.hpp"

#include <fmt/format.h>

#include "core/validation.hpp"

namespace peg3d::game {

nlohmann::json policy_to_json(const FaclPolicy& policy) {
  nlohmann::json doc{{"format", kPolicyFormat},
                     {"version", kPolicyVersion},
                     {"role", to_string(policy.role())},
                     {"config", policy.config()}};
  doc["channels"] = nlohmann::json::array();
  for (int c = 0; c < policy.channels(); ++c) {
    const fuzzy::FaclLearner& l = policy.learner(c);
    const auto actor = l.actor_table();
    const auto critic = l.critic_table();
    doc["channels"].push_back({{"rules", l.rules().rules()},
                               {"actions", l.actions()},
                               {"actor", std::vector<double>(actor.begin(), actor.end())},
                               {"critic", std::vector<double>(critic.begin(), critic.end())}});
  }
  return doc;
}

std::unique_ptr<FaclPolicy> policy_from_json(const nlohmann::json& doc, std::uint64_t seed) {
  try {
    if (!doc.is_object() || doc.value("format", "") != kPolicyFormat) {
      throw PolicyFormatError(fmt::format("not a peg3d policy (expected \"format\": \"{}\")", kPolicyFormat));
    }
    const int version = doc.at("version").get<int>();
    if (version != kPolicyVersion) {
      throw PolicyFormatError(fmt::format("policy version {} is not supported (this build reads {})", version, kPolicyVersion));
    }
    const std::string role_name = doc.at("role").get<std::string>();
    if (role_name != "pursuer" && role_name != "evader") throw PolicyFormatError("role must be pursuer or evader");
    const Role role = role_name == "pursuer" ? Role::kPursuer : Role::kEvader;
    AgentConfig config = doc.at("config").get<AgentConfig>();
    config.policy = "facl";
    auto policy = std::make_unique<FaclPolicy>(config, role, seed);
    const auto& channels = doc.at("channels");
    if (!channels.is_array() || static_cast<int>(channels.size()) != policy->channels()) {
      throw PolicyFormatError(fmt::format("expected {} channels for this configuration", policy->channels()));
    }
    for (int c = 0; c < policy->channels(); ++c) {
      fuzzy::FaclLearner& l = policy->learner(c);
      const auto actor = channels[c].at("actor").get<std::vector<double>>();
      const auto critic = channels[c].at("critic").get<std::vector<double>>();
      if (actor.size() != l.actor_table().size() || critic.size() != l.critic_table().size()) {
        throw PolicyFormatError(fmt::format("channel {}: tables have {} and {} entries, expected {} and {}", c,
                                            actor.size(), critic.size(), l.actor_table().size(), l.critic_table().size()));
      }
      std::copy(actor.begin(), actor.end(), l.actor_table().begin());
      std::copy(critic.begin(), critic.end(), l.critic_table().begin());
    }
    return policy;
  } catch (const nlohmann::json::exception& e) {
    throw PolicyFormatError(std::string("malformed policy: ") + e.what());
  } catch (const InvalidParameter& e) {
    throw PolicyFormatError(std::string("invalid policy configuration: ") + e.what());
  }
}

}  // namespace peg3d::game
