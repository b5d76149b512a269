// peg-paper: the paper's experiment end to end. For every scenario of the map (S1..S4 on maps/paper.yaml)
// and every algorithm (peg3d's FACL, the paper's configuration, the Al-Mahbashi-style baseline), repeats of
// co-learning followed by a greedy evaluation; results, statistics and figures in --out (docs/results.md).
#include "experiment/paper_experiment.hpp"
#include "experiment_main.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-paper: the paper's four scenarios, FACL against the baseline, with statistics and figures"};
  cli::ExperimentOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/paper";
  std::vector<std::string> algorithms{"peg3d", "baseline", "paper"};
  cli::add_experiment_flags(app, o, "SCENARIO_ALGORITHM, e.g. S1_peg3d or '*_peg3d'; the evaluation episode of repeat 0",
                            /*plots=*/true);
  app.add_option("--algorithms", algorithms, "algorithms to compare: presets (" + game::preset_list() + ")")
      ->delimiter(',')
      ->capture_default_str();

  return cli::experiment_main(app, argc, argv, o, [&]() -> std::unique_ptr<experiment::Experiment> {
    auto algs = cli::algorithms_or_listing(algorithms, o);
    if (!algs) return nullptr;
    return std::make_unique<experiment::PaperExperiment>(cli::load_arena(o.map, !o.no_cache), std::move(*algs),
                                                         experiment::PaperSettings{.sweep = o.sweep, .trace_repeat = 0},
                                                         cli::resolve_input(o.map).string());
  });
}
