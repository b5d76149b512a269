#include "experiment/sweep_settings.hpp"

#include "core/random.hpp"
#include "results/run_info.hpp"

namespace peg3d::experiment {

nlohmann::json setup_header(const char* experiment, const world::Arena& map, const SweepSettings& s) {
  return {{"experiment", experiment},
          {"peg3d", results::peg3d_build_json()},
          {"map_hash", results::map_content_hash(map)},
          {"seed", s.seed},
          {"episodes", s.episodes}};
}

std::uint64_t run_seed(std::uint64_t root, int scenario, int repeat) {
  return derive_seed(root, {static_cast<std::uint64_t>(scenario), static_cast<std::uint64_t>(repeat)});
}

nlohmann::ordered_json scenario_run_seeds(const std::vector<world::Scenario>& scenarios, int repeats,
                                          std::uint64_t root) {
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (std::size_t sc = 0; sc < scenarios.size(); ++sc) {
    for (int rep = 0; rep < repeats; ++rep) {
      runs.push_back({{"run", sc * static_cast<std::size_t>(repeats) + static_cast<std::size_t>(rep)},
                      {"scenario", scenarios[sc].name},
                      {"repeat", rep},
                      {"seed", run_seed(root, static_cast<int>(sc), rep)}});
    }
  }
  return runs;
}

}  // namespace peg3d::experiment
