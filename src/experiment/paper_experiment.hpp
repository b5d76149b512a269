#pragma once
// The paper's experiment (section 4): for every scenario of a map and every algorithm, `repeats` trials of
// co-learning from the scenario's start followed by a greedy evaluation. Runs of the same scenario and
// repeat share their seed across algorithms, so algorithms are compared on paired runs.

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/result_files.hpp"
#include "experiment/run_journal.hpp"
#include "experiment/training.hpp"
#include "game/episode.hpp"
#include "game/facl_policy.hpp"
#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

class ProgressReporter;

/// An algorithm of the comparison: a name and the whole game configuration it plays with.
struct Algorithm {
  std::string name;
  game::GameConfig config;
};

/// Builds algorithms from preset names and applies `--set` overrides. An override whose first key is an
/// algorithm's name applies to that algorithm only ("paper.pursuer.facl.actor_rate=0.01"); any other
/// applies to every algorithm ("evader.motion_space=false"). Throws ConfigError / InvalidParameter naming the
/// key.
std::vector<Algorithm> make_algorithms(const std::vector<std::string>& names, const std::vector<std::string>& overrides);

/// Applies overrides to one configuration (no algorithm prefixes) and validates the result.
game::GameConfig apply_game_overrides(game::GameConfig config, const std::vector<std::string>& overrides);

/// The configuration named by `source`: a preset name (peg3d, paper, baseline, robust) or a JSON file holding a
/// GameConfig, read over the peg3d preset (fields it leaves out keep the preset's values; unknown keys and
/// wrong types are errors naming the file and field).
game::GameConfig load_game_config(const std::string& source);

struct SweepSettings {
  std::uint64_t seed = 1;  ///< root seed
  int episodes = 200;      ///< training episodes per run
  int repeats = 20;        ///< runs per scenario and algorithm
  int threads = 0;         ///< worker threads, 0: every core of the CPU affinity (resolve_thread_count)
  int trace_repeat = 0;    ///< repeat whose evaluation is recorded step by step and whose policies are kept
  SweepControl control;    ///< journal and stop request (none by default)
};

struct PaperResults {
  std::vector<RunRecord> runs;                            ///< scenario-major, then algorithm, then repeat
  std::vector<LearningCurve> curves;                      ///< training episodes of each run
  std::map<std::string, game::Trace> traces;              ///< "<scenario>_<algorithm>" -> steps
  /// "<scenario>_<algorithm>_<role>" (a second model of a role: "<role>1", ...) -> trained model
  std::map<std::string, std::shared_ptr<const game::FaclModel>> policies;
  long long steps = 0;                                     ///< simulated steps, training and evaluation
};

/// The seed of a scenario's repeat (shared by all algorithms).
std::uint64_t run_seed(std::uint64_t root, int scenario, int repeat);

/// Every run of a sweep over scenarios x repeats (run = scenario index * repeats + repeat) with its seed, for
/// run_info.json: [{"run", "scenario", "repeat", "seed"}].
nlohmann::ordered_json scenario_run_seeds(const std::vector<world::Scenario>& scenarios, int repeats,
                                          std::uint64_t root);

/// One Sim per algorithm over `arena` (each checks the map's scenarios against its configuration).
std::vector<game::Sim> make_sims(const std::shared_ptr<const world::Arena>& arena, const std::vector<Algorithm>& algorithms);

/// One opponent pool per algorithm (experiment/training.hpp; empty for co-learning), over `arena`.
std::vector<OpponentPool> make_pools(const std::shared_ptr<const world::Arena>& arena, const std::vector<Algorithm>& algorithms);

/// Runs in the sweep: scenarios x algorithms x repeats.
std::size_t paper_run_count(const world::Arena& arena, const std::vector<Algorithm>& algorithms, const SweepSettings& settings);

/// Everything the sweep's results depend on, for its journal header (run_journal.hpp): the experiment, the
/// peg3d build, the map's content hash, seed, episodes, repeats, the traced repeat, and every algorithm's
/// name and effective configuration, in order.
nlohmann::json paper_setup(const world::Arena& arena, const std::vector<Algorithm>& algorithms,
                           const SweepSettings& settings);

/// The part of run_info.json (run_info.hpp) that config.json and runs.csv do not hold already: the traced
/// repeat, and where the configuration and the per-run seeds are.
nlohmann::ordered_json paper_run_info(const SweepSettings& settings);

/// Runs every scenario x algorithm x repeat; sims[k] plays algorithms[k], which trains with pools[k]. Run i is scenario i / (A * R),
/// algorithm (i / R) % A, repeat i % R. With settings.control's journal, finished runs are recorded as they
/// finish and runs it holds are read back instead of run; a stop request throws SweepInterrupted.
PaperResults run_paper_experiment(const std::vector<Algorithm>& algorithms, const std::vector<game::Sim>& sims,
                                  const std::vector<OpponentPool>& pools, const SweepSettings& settings,
                                  ProgressReporter* progress = nullptr);

/// summary.json (docs/results.md): per scenario and algorithm rates and means with 95% intervals, and paired
/// comparisons of every pair of algorithms.
nlohmann::ordered_json summarize(const std::vector<RunRecord>& runs, const std::vector<std::string>& scenarios,
                         const std::vector<std::string>& algorithms, double time_limit);

/// The summary as a plain-text table for stdout.
std::string summary_table(const nlohmann::ordered_json& summary);

}  // namespace peg3d::experiment
