#pragma once
// Generalization: a FACL pair co-trained on one map's scenarios, frozen, then evaluated greedily on every
// scenario of other maps (for instance one with terrain). Reports capture and collision rates per map.

#include <cstdint>
#include <functional>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/sweep_settings.hpp"
#include "experiment/training.hpp"
#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "game/lineup.hpp"
#include "game/sim.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

struct GeneralizeSettings {
  SweepSettings sweep{.repeats = 5};  ///< repeats: training runs per scenario of the training map
  /// The classic opponents mixed into training (experiment/training.hpp); null: co-learning.
  std::shared_ptr<const OpponentPool> pool{};
  /// Chooses the games (by generalize_key) whose episode is recorded, for replay viewers; none when empty.
  std::function<bool(const std::string&)> keep_trace{};
};

struct GeneralizeRecord {
  std::string train_scenario;  ///< scenario of the training map the pair learned on
  int repeat = 0;
  std::string eval_map;        ///< name of the evaluation map
  std::string eval_scenario;
  game::EpisodeResult result;
  std::shared_ptr<const game::Trace> trace;  ///< every instant, when settings.keep_trace chose the game
};

/// A game's key: TRAINSCENARIO_rREPEAT_on_EVALMAP_EVALSCENARIO, e.g. S1_r0_on_forest_S2.
std::string generalize_key(const GeneralizeRecord& r);

/// An evaluation map: its Sim and the name results give it.
struct EvalMap {
  std::string name;  ///< the map's `name`, else its file's stem; unique among the evaluation maps
  game::Sim sim;
};

/// The display names of evaluation maps: each map's `name`, else its file's stem, made unique by appending
/// "-2", "-3", ... to repeats.
std::vector<std::string> eval_map_names(const std::vector<std::shared_ptr<const world::Arena>>& arenas);

/// Runs in the sweep (training scenarios x repeats); run i is scenario i / repeats, repeat i % repeats.
std::size_t generalize_run_count(const game::Sim& train, const GeneralizeSettings& settings);

/// Everything the sweep's results depend on, for its journal header and run_info.json: the experiment, the
/// peg3d build, the training map's content hash, each evaluation map's name and content hash, seed, episodes,
/// repeats and the configuration.
nlohmann::json generalize_setup(const game::Sim& train, const std::vector<EvalMap>& evals,
                                const GeneralizeSettings& settings);

/// The seeds of run_info.json: the root, how seeds derive, and each run's seed.
nlohmann::ordered_json generalize_seeds(const game::Sim& train, const GeneralizeSettings& settings);

/// Trains per training scenario and repeat on `train`, evaluates the frozen models greedily on every scenario
/// of every evaluation map. The trained models of repeat 0 are returned through `keep` as
/// "<train_scenario>_<role>" (a second model of a role: "<role>1", ...) when not null. With
/// settings.sweep.control's journal, finished runs are recorded as they finish and runs it holds are read back
/// instead of run; a stop request throws sweep::SweepInterrupted.
std::vector<GeneralizeRecord> run_generalization(
    const game::Sim& train, const std::vector<EvalMap>& evals, const GeneralizeSettings& settings,
    std::vector<std::pair<std::string, std::shared_ptr<const game::FaclModel>>>* keep = nullptr);

void write_generalization_csv(const std::filesystem::path& file, const std::vector<GeneralizeRecord>& records);

/// Per evaluation map: runs, captures and collision runs with Wilson intervals, mean capture time.
nlohmann::ordered_json summarize_generalization(const std::vector<GeneralizeRecord>& records,
                                                const std::vector<std::string>& maps);
std::string generalization_table(const nlohmann::ordered_json& summary);

}  // namespace peg3d::experiment
