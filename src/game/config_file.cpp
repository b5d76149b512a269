#include "game/config_file.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "core/config_json.hpp"
#include "core/config_overrides.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"

namespace peg3d::game {

GameConfig apply_game_overrides(GameConfig config, const std::vector<std::string>& overrides) {
  nlohmann::json j = config::to_json(config);
  config::apply_overrides(j, overrides);
  config::from_json(j, config);
  config.validate();
  return config;
}

GameConfig load_game_config(const std::string& source) {
  for (const char* name : kPresetNames)
    if (source == name) return preset(source);
  const std::filesystem::path file(source);
  if (file.extension() != ".json") {
    throw InputError(fmt::format("--config {}: neither a preset ({}) nor a .json file", source, preset_list()));
  }
  const std::string text = read_input_file(file, "configuration file");
  const nlohmann::json j = parse_json_text(text, file);
  GameConfig c = preset("peg3d");
  config::from_json(j, c, {file, false, text});
  try {
    c.validate();
  } catch (const InvalidParameter& e) {
    throw InputError(file, json_line_of(text, e.parameter()), e.parameter(), e.message());
  }
  return c;
}

}  // namespace peg3d::game
