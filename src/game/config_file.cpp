#include "game/config_file.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "core/config_json.hpp"
#include "core/config_overrides.hpp"
#include "core/error.hpp"

namespace peg3d::game {

GameConfig apply_game_overrides(GameConfig config, const std::vector<std::string>& overrides, const ConfigCheck& check) {
  nlohmann::json j = config::to_json(config);
  config::apply_overrides(j, overrides);
  config::from_json(j, config);
  config.validate();
  if (check) check(config);
  return config;
}

GameConfig load_game_config(const std::string& source, const ConfigCheck& check) {
  for (const char* name : kPresetNames) {
    if (source == name) {
      GameConfig c = preset(source);
      if (check) check(c);
      return c;
    }
  }
  const std::filesystem::path file(source);
  if (file.extension() != ".json") {
    throw InputError(fmt::format("--config {}: neither a preset ({}) nor a .json file", source, preset_list()));
  }
  GameConfig c = preset("peg3d");
  config::read_config_file(file, c, [&check](const GameConfig& read) {
    read.validate();
    if (check) check(read);
  });
  return c;
}

}  // namespace peg3d::game
