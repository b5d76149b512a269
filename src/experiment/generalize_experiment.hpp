#pragma once
// Generalization: a FACL pair co-trained on one map's scenarios, frozen, then evaluated greedily on every
// scenario of other maps (for instance one with terrain). Reports capture and collision rates per map.

#include <cstdint>
#include <functional>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/experiment.hpp"
#include "experiment/trial.hpp"
#include "experiment/sweep_settings.hpp"
#include "experiment/training.hpp"
#include "experiment/trial_config.hpp"
#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "players/lineup.hpp"
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
nlohmann::json generalize_setup(const game::Sim& train, const TrialConfig& config, const std::vector<EvalMap>& evals,
                                const GeneralizeSettings& settings);

/// The seeds of run_info.json: the root, how seeds derive, and each run's seed.
nlohmann::ordered_json generalize_seeds(const game::Sim& train, const GeneralizeSettings& settings);

void write_generalization_csv(const std::filesystem::path& file, const std::vector<GeneralizeRecord>& records);

/// Per evaluation map: runs, captures and collision runs with Wilson intervals, mean capture time.
nlohmann::ordered_json summarize_generalization(const std::vector<GeneralizeRecord>& records,
                                                const std::vector<std::string>& maps);
std::string generalization_table(const nlohmann::ordered_json& summary);

/// The generalization as an Experiment: run i (training scenario i / repeats, repeat i % repeats) trains on the
/// training map, then plays the frozen models greedily on every scenario of every evaluation map. Result files
/// (docs/results.md): generalization.csv, summary.json, and policies/ with repeat 0's trained models, as
/// "<train_scenario>_<role>" (a second model of a role: "<role>1", ...).
class GeneralizeExperiment : public Experiment {
 public:
  /// Builds the training Sim and one per evaluation map, each checking its map's starts against the agents,
  /// and, unless settings.pool is set, the classic opponents training mixes in.
  GeneralizeExperiment(std::shared_ptr<const world::Arena> train, std::vector<std::shared_ptr<const world::Arena>> evals,
                       const TrialConfig& config, GeneralizeSettings settings);

  std::string kind() const override { return "generalize"; }
  nlohmann::json setup() const override { return generalize_setup(train_, config_, evals_, settings_); }
  std::size_t run_count() const override { return generalize_run_count(train_, settings_); }
  std::size_t episodes_per_run() const override;
  void begin(const sweep::SweepControl& control) override;
  void run_one(std::size_t i) override;
  nlohmann::json encode(std::size_t i) const override;
  void restore(std::size_t i, const nlohmann::json& record) override;
  void finish(bool root) override;
  void record_episodes(std::function<bool(const std::string&)> chosen) override { settings_.keep_trace = std::move(chosen); }
  void write_results(const std::filesystem::path& out, const SweepTiming& timing) const override;
  std::vector<std::pair<std::string, const world::Arena*>> maps() const override;
  nlohmann::ordered_json run_info() const override;
  std::vector<RecordedEpisode> recorded() const override;
  std::string report(const SweepTiming& timing) const override;

  /// Every game, in run order, once finish(true) has gathered them.
  const std::vector<GeneralizeRecord>& records() const { return records_; }

 private:
  // Run i's slot in kept_ (repeat 0 of its training scenario); nullopt for the other repeats.
  std::optional<std::size_t> kept_slot(std::size_t i) const;

  TrialConfig config_;
  game::Sim train_;
  std::vector<EvalMap> evals_;
  GeneralizeSettings settings_;
  std::vector<std::vector<GeneralizeRecord>> per_run_;
  std::vector<TrialResult> kept_;  ///< repeat 0's trained models, per training scenario
  std::vector<GeneralizeRecord> records_;
  nlohmann::ordered_json summary_;
};

}  // namespace peg3d::experiment
