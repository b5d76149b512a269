#include "experiment/algorithms.hpp"

#include <set>

#include "core/config_json.hpp"
#include "core/config_overrides.hpp"
#include "core/error.hpp"
#include "core/validation.hpp"

namespace peg3d::experiment {

std::vector<Algorithm> make_algorithms(const std::vector<std::string>& names, const std::vector<std::string>& overrides) {
  std::vector<Algorithm> out;
  std::set<std::string> seen;
  for (const std::string& entry : names) {
    // "NAME=PRESET" names a variant of a preset, so one preset can enter twice with different overrides.
    const std::size_t eq = entry.find('=');
    const std::string name = entry.substr(0, eq);
    const std::string preset = eq == std::string::npos ? entry : entry.substr(eq + 1);
    if (name.empty() || name.find_first_of(".= ,") != std::string::npos) {
      throw InvalidParameter("--algorithms", entry, "an algorithm's name must be non-empty, without '.', '=', ',' or spaces");
    }
    if (!seen.insert(name).second) throw InputError("algorithm '" + name + "' is listed twice");
    out.push_back({name, trial_preset(preset)});
  }
  std::vector<nlohmann::json> configs;
  for (const Algorithm& a : out) configs.push_back(config::to_json(a.config));
  for (const std::string& o : overrides) {
    const std::size_t dot = o.find('.'), eq = o.find('=');
    const std::string head = o.substr(0, std::min(dot, eq));
    bool targeted = false;
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (out[i].name == head && dot < eq) {
        config::apply_override(configs[i], std::string_view(o).substr(dot + 1));
        targeted = true;
      }
    }
    if (!targeted) {
      for (auto& c : configs) config::apply_override(c, o);
    }
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    config::from_json(configs[i], out[i].config);
    out[i].config.validate();
  }
  return out;
}

std::vector<game::Sim> make_sims(const std::shared_ptr<const world::Arena>& arena, const std::vector<Algorithm>& algorithms) {
  std::vector<game::Sim> sims;
  sims.reserve(algorithms.size());
  for (const Algorithm& a : algorithms) sims.emplace_back(arena, a.config.game);
  return sims;
}

std::vector<OpponentPool> make_pools(const std::shared_ptr<const world::Arena>& arena, const std::vector<Algorithm>& algorithms) {
  std::vector<OpponentPool> pools;
  pools.reserve(algorithms.size());
  for (const Algorithm& a : algorithms) pools.push_back(make_pool(arena, a.config.game, a.config.training));
  return pools;
}

nlohmann::json algorithms_json(const std::vector<Algorithm>& algorithms) {
  nlohmann::json algs = nlohmann::json::array();
  for (const Algorithm& a : algorithms) algs.push_back({{"name", a.name}, {"config", config::to_json(a.config)}});
  return algs;
}

}  // namespace peg3d::experiment
