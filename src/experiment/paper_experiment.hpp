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

#include "experiment/algorithms.hpp"
#include "experiment/sweep_settings.hpp"
#include "experiment/training.hpp"
#include "game/episode.hpp"
#include "game/facl_policy.hpp"
#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "results/result_files.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

/// The paper's sweep: what every sweep has (repeats per scenario and algorithm, 20 by default) and the repeat
/// whose evaluation is recorded step by step and whose trained policies are kept.
struct PaperSettings {
  SweepSettings sweep;
  int trace_repeat = 0;  ///< in [0, repeats)
};

struct PaperResults {
  std::vector<results::RunRecord> runs;        ///< scenario-major, then algorithm, then repeat
  std::vector<results::LearningCurve> curves;  ///< training episodes of each run
  std::map<std::string, game::Trace> traces;   ///< "<scenario>_<algorithm>" -> steps
  /// "<scenario>_<algorithm>_<role>" (a second model of a role: "<role>1", ...) -> trained model
  std::map<std::string, std::shared_ptr<const game::FaclModel>> policies;
  long long steps = 0;  ///< simulated steps, training and evaluation
};

/// Runs in the sweep: scenarios x algorithms x repeats.
std::size_t paper_run_count(const world::Arena& arena, const std::vector<Algorithm>& algorithms,
                            const PaperSettings& settings);

/// Everything the sweep's results depend on, for its journal header (sweep/run_journal.hpp): the experiment,
/// the peg3d build, the map's content hash, seed, episodes, repeats, the traced repeat, and every algorithm's
/// name and effective configuration, in order.
nlohmann::json paper_setup(const world::Arena& arena, const std::vector<Algorithm>& algorithms,
                           const PaperSettings& settings);

/// The part of run_info.json (results/run_info.hpp) that config.json and runs.csv do not hold already: the
/// traced repeat, and where the configuration and the per-run seeds are.
nlohmann::ordered_json paper_run_info(const PaperSettings& settings);

/// Runs every scenario x algorithm x repeat; sims[k] plays algorithms[k], which trains with pools[k]. Run i is
/// scenario i / (A * R), algorithm (i / R) % A, repeat i % R. With settings.sweep.control's journal, finished runs are recorded as
/// they finish and runs it holds are read back instead of run; a stop request throws sweep::SweepInterrupted.
PaperResults run_paper_experiment(const std::vector<Algorithm>& algorithms, const std::vector<game::Sim>& sims,
                                  const std::vector<OpponentPool>& pools, const PaperSettings& settings);

/// summary.json (docs/results.md): per scenario and algorithm rates and means with 95% intervals, and paired
/// comparisons of every pair of algorithms.
nlohmann::ordered_json summarize(const std::vector<results::RunRecord>& runs, const std::vector<std::string>& scenarios,
                                 const std::vector<std::string>& algorithms, double time_limit);

/// The summary as a plain-text table for stdout.
std::string summary_table(const nlohmann::ordered_json& summary);

}  // namespace peg3d::experiment
