#pragma once
// A game configuration as a user gives it: a preset's name or a JSON file, and `--set key=value` overrides
// (core/config_overrides.hpp) applied over it. Every error names the file, line and field, or the key.

#include <string>
#include <vector>

#include "game/game_config.hpp"

namespace peg3d::game {

/// The configuration named by `source`: a preset name (kPresetNames) or a JSON file holding a
/// GameConfig, read over the peg3d preset (fields it leaves out keep the preset's values; unknown keys and
/// wrong types are errors naming the file and field).
GameConfig load_game_config(const std::string& source);

/// Applies `key=value` overrides to one configuration and validates the result. Throws ConfigError /
/// InvalidParameter naming the key.
GameConfig apply_game_overrides(GameConfig config, const std::vector<std::string>& overrides);

}  // namespace peg3d::game
