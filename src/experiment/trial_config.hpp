#pragma once
// What an experiment's trial is configured by: the game (game/game_config.hpp) and how its learners train
// (experiment/training.hpp). Its JSON image is the game's fields with a "training" section beside them, as
// configuration files, `--set` and result files write it; the presets give both parts.

#include <concepts>
#include <string>
#include <type_traits>
#include <vector>

#include "core/config_fields.hpp"
#include "experiment/training.hpp"
#include "game/game_config.hpp"

namespace peg3d::experiment {

struct TrialConfig {
  game::GameConfig game;
  TrainingConfig training;
  void validate() const;
  bool operator==(const TrialConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, TrialConfig>
void visit_fields(V& v, C& c) {
  v.embed(c.game);  // the game's fields at the top level, as configuration files have them
  v.section("training", c.training, "how FACL agents train (docs/learning.md)");
}

/// A preset by name (game::kPresetNames): the game's (game::preset) and how it trains. "robust" trains with the
/// opponent pool; the others co-learn, as the paper does. Throws InvalidParameter for an unknown name.
TrialConfig trial_preset(const std::string& name);

/// The configuration named by `source`, a preset name or a JSON file read over the peg3d preset, with `key=value`
/// overrides applied; validated, and every agent's policy checked against the players' registry
/// (players::check_players). Errors name the file, line and field, or the key.
TrialConfig load_trial_config(const std::string& source, const std::vector<std::string>& overrides = {});

/// Applies overrides to `config`, validates it and checks its players, as load_trial_config does.
TrialConfig apply_trial_overrides(TrialConfig config, const std::vector<std::string>& overrides);

}  // namespace peg3d::experiment
