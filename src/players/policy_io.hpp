#pragma once
// Trained FACL models as versioned JSON documents, and their files: the agent's role and configuration (which fix the rule
// bases) and every channel's actor and critic consequents. Doubles are written with round-trip precision,
// so a loaded model acts exactly as the saved one.
//
//   {"format": "peg3d-policy", "version": 7, "role": "pursuer", "config": {...AgentConfig, every field...},
//    "channels": [{"rules": 625, "actions": 1, "actor": [...], "critic": [...]}, ...]}
//
// Versions: 2 added config.guard.faces, 3 config.guard.look_ahead, 4 config.observation.opponent_heading,
// 5 config.action, 6 config.lidar, config.map and config.observation.obstacles, 7 config.map.insert_agents. Older
// documents still load, read as their agents played: version 6 maps with the agents' echoes in them; without a
// lidar or a map, sensing the world,
// actions as heading changes,
// without the opponent's heading (false), without the look ahead (guard.look_ahead = 0) and, version 1,
// without guard.faces (false).

#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "players/facl_policy.hpp"

namespace peg3d::players {

inline constexpr const char* kPolicyFormat = "peg3d-policy";
inline constexpr int kPolicyVersion = 10;  // 8: AgentConfig::sight; 9: its depth camera; 10: sight inputs
/// The oldest version this build reads.
inline constexpr int kOldestPolicyVersion = 1;

/// A policy document that cannot be used: what() names the file and the field at fault.
class PolicyFormatError : public InputError {
 public:
  using InputError::InputError;
};

nlohmann::json policy_to_json(const FaclModel& model);

/// Rebuilds a model from its document. Throws PolicyFormatError (naming `file`) on a wrong format, an
/// unsupported version, a configuration with missing, unknown or invalid fields, tables of the wrong shape
/// or with non-finite values, and, when `expected_role` is given, a policy saved for the other role. With the
/// document's source `text`, errors name the line of the field at fault.
std::shared_ptr<FaclModel> policy_from_json(const nlohmann::json& document, const std::filesystem::path& file = {},
                                            std::optional<game::Role> expected_role = std::nullopt,
                                            std::string_view text = {});

/// Saves a trained FACL model as its document, pretty-printed, atomically (complete or absent).
void save_policy(const std::filesystem::path& file, const FaclModel& model);

/// A policy file's text and its JSON, read once (FACL and MLP policy files alike).
struct PolicyDocument {
  std::string text;
  nlohmann::json doc;
};
/// Reads and parses a policy file; one that cannot be read or is not JSON is a PolicyFormatError naming it.
PolicyDocument read_policy_document(const std::filesystem::path& file);

/// Loads a policy document for an agent of `role`. Throws PolicyFormatError (an InputError) naming the file
/// when it cannot be read, is not JSON, does not fit, or was saved for the other role.
std::shared_ptr<FaclModel> load_policy(const std::filesystem::path& file, game::Role role);

}  // namespace peg3d::players
