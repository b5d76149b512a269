#pragma once
// Generalization: a FACL pair co-trained on one map's scenarios, frozen, then evaluated greedily on every
// scenario of other maps (for instance one with terrain). Reports capture and collision rates per map.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "game/lineup.hpp"
#include "game/sim.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

class ProgressReporter;

struct GeneralizeSettings {
  std::uint64_t seed = 1;
  int episodes = 200;
  int repeats = 5;
  int threads = 0;
};

struct GeneralizeRecord {
  std::string train_scenario;  ///< scenario of the training map the pair learned on
  int repeat = 0;
  std::string eval_map;        ///< name of the evaluation map
  std::string eval_scenario;
  game::EpisodeResult result;
};

/// An evaluation map: its Sim and the name results give it.
struct EvalMap {
  std::string name;  ///< the map's `name`, else its file's stem; unique among the evaluation maps
  game::Sim sim;
};

/// The display names of evaluation maps: each map's `name`, else its file's stem, made unique by appending
/// "-2", "-3", ... to repeats.
std::vector<std::string> eval_map_names(const std::vector<std::shared_ptr<const world::Arena>>& arenas);

/// Trains per training scenario and repeat on `train`, evaluates the frozen models greedily on every scenario
/// of every evaluation map. The trained models of repeat 0 are returned through `keep` as
/// "<train_scenario>_<role>" (a second model of a role: "<role>1", ...) when not null.
std::vector<GeneralizeRecord> run_generalization(
    const game::Sim& train, const std::vector<EvalMap>& evals, const GeneralizeSettings& settings,
    ProgressReporter* progress = nullptr,
    std::vector<std::pair<std::string, std::shared_ptr<const game::FaclModel>>>* keep = nullptr);

void write_generalization_csv(const std::filesystem::path& file, const std::vector<GeneralizeRecord>& records);

/// Per evaluation map: runs, captures and collision runs with Wilson intervals, mean capture time.
nlohmann::ordered_json summarize_generalization(const std::vector<GeneralizeRecord>& records,
                                                const std::vector<std::string>& maps);
std::string generalization_table(const nlohmann::ordered_json& summary);

}  // namespace peg3d::experiment
