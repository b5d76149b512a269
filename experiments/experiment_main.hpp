#pragma once
// The one program every experiment binary runs once it has declared its own flags: parse, build the
// experiment, run it as a sweep (journal, resume, signals, MPI ranks), and on the root write its results,
// run_info.json, figures, viewer files and report. A binary's main declares flags and says how to build its
// experiment::Experiment from them; nothing else (docs/architecture.md, "Adding an experiment").

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "experiment/algorithms.hpp"
#include "experiment/experiment.hpp"

namespace peg3d::cli {

/// The flags every experiment binary has: the sweep's (add_sweep_options), and --html, --no-plots,
/// --list-config and --list-players, which its main declares when the experiment has them (add_experiment_flags).
struct ExperimentOptions : SweepOptions {
  std::vector<std::string> html;  ///< --html patterns: the recorded episodes written as viewer files
  bool plots = true;              ///< false: --no-plots
  bool list_config = false;       ///< --list-config: print the configuration and stop
};

/// add_sweep_options, --list-config, --list-players (prints the players' registry and exits), then --html (when
/// `html_keys` names the keys episodes have) and --no-plots (when `plots`).
void add_experiment_flags(CLI::App& app, ExperimentOptions& o, const std::string& html_keys, bool plots);

/// Builds the experiment from the parsed flags; null when the flags asked for something else, done already
/// (--list-config).
using MakeExperiment = std::function<std::unique_ptr<experiment::Experiment>()>;

/// The whole program (sweep_main: exit status 2 for input errors, 128 + a signal for a stopped sweep, MPI
/// ranks): builds the experiment, opens the sweep in o.out (open_sweep), runs it (run_stoppable), then on the
/// root writes its result files and run_info.json, removes the journal, draws its figures (unless --no-plots),
/// writes the viewer files the --html patterns choose among its recorded episodes, and prints its report and
/// "results in OUT".
int experiment_main(CLI::App& app, int argc, char** argv, const ExperimentOptions& o, const MakeExperiment& make);

/// The algorithms the presets `names` give, with --set applied (experiment::make_algorithms); with --list-config,
/// prints every configuration field of each, under "# NAME", and returns nullopt.
std::optional<std::vector<experiment::Algorithm>> algorithms_or_listing(const std::vector<std::string>& names,
                                                                        const ExperimentOptions& o);

/// One configuration, a preset or a JSON file (experiment::load_trial_config), with --set applied; with
/// --list-config, prints every field and returns nullopt.
std::optional<experiment::TrialConfig> config_or_listing(const std::string& source, const ExperimentOptions& o);

}  // namespace peg3d::cli
