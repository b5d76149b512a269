#pragma once
// A game configuration as a user gives it: a preset's name or a JSON file, and `--set key=value` overrides
// (core/config_overrides.hpp) applied over it. Every error names the file, line and field, or the key.

#include <functional>
#include <string>
#include <vector>

#include "game/game_config.hpp"

namespace peg3d::game {

/// A rule a configuration must also follow, beyond its own table's (players::check_players: every policy a player
/// of the registry). Throws InvalidParameter naming the field.
using ConfigCheck = std::function<void(const GameConfig&)>;

/// The configuration named by `source`: a preset name (kPresetNames) or a JSON file holding a
/// GameConfig, read over the peg3d preset (fields it leaves out keep the preset's values; unknown keys and
/// wrong types are errors naming the file and field). Validated, then checked by `check` when given.
GameConfig load_game_config(const std::string& source, const ConfigCheck& check = {});

/// Applies `key=value` overrides to one configuration, validates the result and checks it by `check` when given.
/// Throws ConfigError / InvalidParameter naming the key.
GameConfig apply_game_overrides(GameConfig config, const std::vector<std::string>& overrides, const ConfigCheck& check = {});

}  // namespace peg3d::game
