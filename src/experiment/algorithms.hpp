#pragma once
// The algorithms an experiment compares: each a name and the whole configuration it plays and trains with (a
// preset, with `--set` overrides), and what is built from them once per sweep, before any run.

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/training.hpp"
#include "experiment/trial_config.hpp"
#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

/// An algorithm of the comparison: a name and the whole configuration it plays and trains with.
struct Algorithm {
  std::string name;
  TrialConfig config;
};

/// Builds algorithms from preset names, each `PRESET` or `NAME=PRESET` (a named variant, so that one preset can
/// enter twice), and applies `--set` overrides. An override whose first key is an
/// algorithm's name applies to that algorithm only ("paper.pursuer.facl.actor_rate=0.01"); any other
/// applies to every algorithm ("evader.motion_space=false"). Throws ConfigError / InvalidParameter naming the
/// key, InputError for a name listed twice.
std::vector<Algorithm> make_algorithms(const std::vector<std::string>& names, const std::vector<std::string>& overrides);

/// One Sim per algorithm over `arena` (each checks the map's scenarios against its configuration).
std::vector<game::Sim> make_sims(const std::shared_ptr<const world::Arena>& arena, const std::vector<Algorithm>& algorithms);

/// One opponent pool per algorithm (experiment/training.hpp; empty for co-learning), over `arena`.
std::vector<OpponentPool> make_pools(const std::shared_ptr<const world::Arena>& arena, const std::vector<Algorithm>& algorithms);

/// [{"name", "config"}] of every algorithm, in order: the part of a journal header that names them.
nlohmann::json algorithms_json(const std::vector<Algorithm>& algorithms);

}  // namespace peg3d::experiment
