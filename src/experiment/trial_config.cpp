#include "experiment/trial_config.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "core/config_json.hpp"
#include "core/config_overrides.hpp"
#include "core/error.hpp"
#include "players/registry.hpp"

namespace peg3d::experiment {

void TrialConfig::validate() const {
  config::validate(*this);
  players::check_players(game);
}

TrialConfig trial_preset(const std::string& name) {
  TrialConfig c{game::preset(name), {}};
  if (name == "robust") {
    // Co-learning mixed with classic opponents (docs/learning.md).
    c.training.procedure = TrainingProcedure::kOpponentPool;
    c.training.pool.share = 0.8;
    // Every training episode starts at random places, and the evaders learn for twice as long as the pursuers:
    // on the selection seeds the evader then outlasted flee-apollonius against the Apollonius interceptor
    // (docs/learning.md, "Random starts, and a longer training for the evader").
    c.training.random_starts = 1.0;
    c.training.pursuer_learning = 0.5;
  }
  return c;
}

TrialConfig apply_trial_overrides(TrialConfig config, const std::vector<std::string>& overrides) {
  if (!overrides.empty()) {
    nlohmann::json j = config::to_json(config);
    config::apply_overrides(j, overrides);
    config::from_json(j, config);
  }
  config.validate();
  return config;
}

TrialConfig load_trial_config(const std::string& source, const std::vector<std::string>& overrides) {
  for (const char* name : game::kPresetNames) {
    if (source == name) return apply_trial_overrides(trial_preset(source), overrides);
  }
  const std::filesystem::path file(source);
  if (file.extension() != ".json") {
    throw InputError(fmt::format("--config {}: neither a preset ({}) nor a .json file", source, game::preset_list()));
  }
  TrialConfig c = trial_preset("peg3d");
  config::read_config_file(file, c, [](const TrialConfig& read) { read.validate(); });
  return apply_trial_overrides(std::move(c), overrides);
}

}  // namespace peg3d::experiment
