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
#include "experiment/experiment.hpp"
#include "experiment/sweep_settings.hpp"
#include "experiment/training.hpp"
#include "experiment/trial.hpp"
#include "game/episode.hpp"
#include "players/facl_policy.hpp"
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
  std::map<std::string, std::shared_ptr<const players::FaclModel>> policies;
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

/// The paper's sweep as an Experiment: every scenario x algorithm x repeat. Run i is scenario i / (A * R),
/// algorithm (i / R) % A, repeat i % R; algorithm k trains and plays with its own Sim and opponent pool.
/// Result files (docs/results.md): config.json, runs.csv, learning_curves.csv, summary.json, trajectories/ and
/// policies/ of the traced repeat, map.json, apollonius.json, timing.json; figures by tools/plot_paper.py.
class PaperExperiment : public Experiment {
 public:
  /// Builds a Sim and an opponent pool per algorithm; each Sim checks every start against its agents' radii.
  /// `map_file` is the map's path as config.json names it.
  PaperExperiment(std::shared_ptr<const world::Arena> arena, std::vector<Algorithm> algorithms, PaperSettings settings,
                  std::string map_file);

  std::string kind() const override { return "paper"; }
  nlohmann::json setup() const override { return paper_setup(*arena_, algorithms_, settings_); }
  std::size_t run_count() const override { return paper_run_count(*arena_, algorithms_, settings_); }
  std::size_t episodes_per_run() const override { return static_cast<std::size_t>(settings_.sweep.episodes) + 1; }
  void begin(const sweep::SweepControl& control) override;
  void run_one(std::size_t i) override;
  nlohmann::json encode(std::size_t i) const override;
  void restore(std::size_t i, const nlohmann::json& record) override;
  void finish(bool root) override;
  void write_results(const std::filesystem::path& out, const SweepTiming& timing) const override;
  std::vector<std::pair<std::string, const world::Arena*>> maps() const override { return {{"map", arena_.get()}}; }
  nlohmann::ordered_json run_info() const override { return paper_run_info(settings_); }
  std::vector<RecordedEpisode> recorded() const override;
  std::string report(const SweepTiming& timing) const override;
  std::string plot_script() const override { return "plot_paper.py"; }

  /// The results, once finish(true) has gathered them: runs in run order, the traced repeat's steps and models.
  const PaperResults& results() const { return results_; }

 private:
  bool traced(std::size_t i) const { return static_cast<int>(i % settings_.sweep.repeats) == settings_.trace_repeat; }

  std::shared_ptr<const world::Arena> arena_;
  std::vector<Algorithm> algorithms_;
  PaperSettings settings_;
  std::string map_file_;
  std::vector<game::Sim> sims_;       ///< per algorithm
  std::vector<OpponentPool> pools_;   ///< per algorithm
  sweep::SweepControl control_;
  std::vector<TrialResult> trials_;   ///< per run, until finish() moves them into results_
  PaperResults results_;
  nlohmann::ordered_json summary_;
};

/// summary.json (docs/results.md): per scenario and algorithm rates and means with 95% intervals, and paired
/// comparisons of every pair of algorithms.
nlohmann::ordered_json summarize(const std::vector<results::RunRecord>& runs, const std::vector<std::string>& scenarios,
                                 const std::vector<std::string>& algorithms, double time_limit);

/// The summary as a plain-text table for stdout.
std::string summary_table(const nlohmann::ordered_json& summary);

}  // namespace peg3d::experiment
