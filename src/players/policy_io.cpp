#include "players/policy_io.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/config_json.hpp"
#include "core/input_files.hpp"
#include "core/validation.hpp"
#include "players/registry.hpp"

namespace peg3d::players {

nlohmann::json policy_to_json(const FaclModel& model) {
  nlohmann::json doc{{"format", kPolicyFormat},
                     {"version", kPolicyVersion},
                     {"role", to_string(model.role())},
                     {"config", config::to_json(model.config())}};
  doc["channels"] = nlohmann::json::array();
  for (int c = 0; c < model.channels(); ++c) {
    const fuzzy::FaclTables& t = model.tables(c);
    const auto actor = t.actor_table();
    const auto critic = t.critic_table();
    doc["channels"].push_back({{"rules", t.rules().rules()},
                               {"actions", t.actions()},
                               {"actor", std::vector<double>(actor.begin(), actor.end())},
                               {"critic", std::vector<double>(critic.begin(), critic.end())}});
  }
  return doc;
}

namespace {

const nlohmann::json& member(const nlohmann::json& j, const char* key, const std::filesystem::path& file,
                             const std::string& field) {
  const auto it = j.find(key);
  if (it == j.end()) throw PolicyFormatError(file, 0, field, "missing");
  return *it;
}

void read_table(const nlohmann::json& channel, const char* key, std::span<double> out, const std::filesystem::path& file,
                const std::string& field) {
  const nlohmann::json& j = member(channel, key, file, field);
  if (!j.is_array()) throw PolicyFormatError(file, 0, field, "expects a list of numbers");
  if (j.size() != out.size()) {
    throw PolicyFormatError(file, 0, field,
                            fmt::format("has {} entries, this configuration needs {}", j.size(), out.size()));
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!j[i].is_number()) throw PolicyFormatError(file, 0, fmt::format("{}[{}]", field, i), "expects a number, got " + brief(j[i]));
    out[i] = j[i].get<double>();
    if (!std::isfinite(out[i])) throw PolicyFormatError(file, 0, fmt::format("{}[{}]", field, i), "must be finite");
  }
}

}  // namespace

namespace {

std::shared_ptr<FaclModel> read_policy(const nlohmann::json& doc, const std::filesystem::path& file,
                                       std::optional<game::Role> expected_role) {
  if (!doc.is_object() || !doc.contains("format") || doc["format"] != kPolicyFormat) {
    throw PolicyFormatError(file, 0, "format", fmt::format("not a peg3d policy (expected \"format\": \"{}\")", kPolicyFormat));
  }
  const nlohmann::json& version = member(doc, "version", file, "version");
  if (!version.is_number_integer() || version.get<long long>() < kOldestPolicyVersion ||
      version.get<long long>() > kPolicyVersion) {
    throw PolicyFormatError(file, 0, "version",
                            fmt::format("policy version {} is not supported (this build reads {} to {})", brief(version),
                                        kOldestPolicyVersion, kPolicyVersion));
  }
  const nlohmann::json& role_node = member(doc, "role", file, "role");
  if (role_node != "pursuer" && role_node != "evader") {
    throw PolicyFormatError(file, 0, "role", "must be \"pursuer\" or \"evader\", got " + brief(role_node));
  }
  const game::Role role = role_node == "pursuer" ? game::Role::kPursuer : game::Role::kEvader;
  if (expected_role && *expected_role != role) {
    throw PolicyFormatError(file, 0, "role",
                            fmt::format("this is a saved {} policy; it cannot play the {}", to_string(role),
                                        to_string(*expected_role)));
  }
  // The configuration's own messages name its field; prefix the file and "config".
  const auto config_error = [&](const InputError& e) {
    return PolicyFormatError(file, 0, e.field().empty() ? "config" : "config." + e.field(), e.message());
  };
  game::AgentConfig config;
  std::shared_ptr<FaclModel> model;
  try {
    nlohmann::json image = member(doc, "config", file, "config");
    // Fields that older versions predate, as those agents played: version 1 without guard.faces, versions
    // 1 and 2 without guard.look_ahead, versions 1 to 3 without observation.opponent_heading, versions 1 to
    // 4 without action, versions 1 to 5 without lidar, map and observation.obstacles, version 6 without
    // map.insert_agents (its maps held the agents' echoes), versions 1 to 7 without sight (full information),
    // versions 1 to 8 without camera, versions 1 to 9 without observation.sight_inputs and sight_age_range.
    if (image.is_object() && image.contains("guard") && image["guard"].is_object()) {
      nlohmann::json& guard = image["guard"];
      if (version.get<long long>() < 2 && !guard.contains("faces")) guard["faces"] = false;
      if (version.get<long long>() < 3 && !guard.contains("look_ahead")) guard["look_ahead"] = 0.0;
    }
    if (image.is_object() && image.contains("observation") && image["observation"].is_object()) {
      nlohmann::json& observation = image["observation"];
      if (version.get<long long>() < 4 && !observation.contains("opponent_heading")) {
        observation["opponent_heading"] = false;
      }
      if (version.get<long long>() < 10) {
        const game::ObservationConfig defaults;
        if (!observation.contains("sight_inputs")) observation["sight_inputs"] = defaults.sight_inputs;
        if (!observation.contains("sight_age_range")) observation["sight_age_range"] = defaults.sight_age_range;
      }
    }
    if (image.is_object() && version.get<long long>() < 5 && !image.contains("action")) {
      image["action"] = config::enum_name(game::kFaclActionNames, game::FaclAction::kHeadingChange);
    }
    if (image.is_object() && version.get<long long>() < 6) {
      if (!image.contains("lidar")) image["lidar"] = config::to_json(sense::LidarConfig{});
      if (!image.contains("map")) image["map"] = config::to_json(sense::ScanMapConfig{});
      if (image.contains("observation") && image["observation"].is_object() && !image["observation"].contains("obstacles")) {
        image["observation"]["obstacles"] = config::enum_name(game::kObstacleSourceNames, game::ObstacleSource::kWorld);
      }
    }
    if (image.is_object() && version.get<long long>() < 7 && image.contains("map") && image["map"].is_object() &&
        !image["map"].contains("insert_agents")) {
      image["map"]["insert_agents"] = true;  // version 6 put the agents' echoes into the map
    }
    if (image.is_object() && version.get<long long>() < 8 && !image.contains("sight")) {
      image["sight"] = config::to_json(sense::SightConfig{});
    }
    if (image.is_object() && version.get<long long>() < 9 && !image.contains("camera")) {
      image["camera"] = config::to_json(sense::DepthCameraConfig{});
    }
    config::from_json(image, config, {{}, /*complete=*/true, {}});
    config::validate(config);
    if (config.policy != kFacl) throw InvalidParameter("policy", config.policy, "must be facl");
    model = std::make_shared<FaclModel>(config, role);
  } catch (const PolicyFormatError&) {
    throw;
  } catch (const InputError& e) {
    throw config_error(e);
  }
  const nlohmann::json& channels = member(doc, "channels", file, "channels");
  if (!channels.is_array() || static_cast<int>(channels.size()) != model->channels()) {
    throw PolicyFormatError(file, 0, "channels", fmt::format("expected a list of {} channels for this configuration", model->channels()));
  }
  for (int c = 0; c < model->channels(); ++c) {
    fuzzy::FaclTables& t = model->tables(c);
    const nlohmann::json& ch = channels[std::size_t(c)];
    const std::string field = fmt::format("channels[{}]", c);
    if (!ch.is_object()) throw PolicyFormatError(file, 0, field, "expects an object");
    const nlohmann::json& rules = member(ch, "rules", file, field + ".rules");
    const nlohmann::json& actions = member(ch, "actions", file, field + ".actions");
    if (rules != t.rules().rules() || actions != t.actions()) {
      throw PolicyFormatError(file, 0, field, fmt::format("has {} rules and {} actions, this configuration needs {} and {}",
                                                          brief(rules), brief(actions), t.rules().rules(), t.actions()));
    }
    read_table(ch, "actor", t.actor_table(), file, field + ".actor");
    read_table(ch, "critic", t.critic_table(), file, field + ".critic");
  }
  return model;
}

}  // namespace

std::shared_ptr<FaclModel> policy_from_json(const nlohmann::json& doc, const std::filesystem::path& file,
                                            std::optional<game::Role> expected_role, std::string_view text) {
  try {
    return read_policy(doc, file, expected_role);
  } catch (const PolicyFormatError& e) {
    // The tables are read without their text: find the field's line only now that something is wrong.
    if (e.line() != 0 || text.empty() || e.field().empty()) throw;
    throw PolicyFormatError(file, json_line_of(text, e.field()), e.field(), e.message());
  }
}

void save_policy(const std::filesystem::path& file, const FaclModel& model) {
  write_file_atomically(file, policy_to_json(model).dump(2) + "\n");
}

PolicyDocument read_policy_document(const std::filesystem::path& file) {
  PolicyDocument d;
  try {
    d.text = read_input_file(file, "policy file");
    d.doc = parse_json_text(d.text, file);
  } catch (const InputError& e) {
    throw PolicyFormatError(file, e.line(), e.field(), e.message());
  }
  return d;
}

std::shared_ptr<FaclModel> load_policy(const std::filesystem::path& file, game::Role role) {
  const PolicyDocument d = read_policy_document(file);
  return policy_from_json(d.doc, file, role, d.text);
}

}  // namespace peg3d::players
