// peg-generalize: train FACL agents on one map, freeze them, and evaluate them on other maps (one with
// terrain among them); capture and collision rates per evaluation map.
#include "experiment/generalize_experiment.hpp"
#include "experiment_main.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-generalize: train on one map, evaluate the saved policies on others"};
  cli::ExperimentOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/generalize";
  o.sweep.repeats = 5;
  std::string config_source = "peg3d";
  std::vector<std::filesystem::path> eval_maps{"maps/paper.yaml", "maps/forest.yaml", "maps/valley.yaml"};
  cli::add_experiment_flags(app, o, "TRAIN_rREPEAT_on_EVALMAP_EVALSCENARIO, e.g. S1_r0_on_forest_S2 or '*_r0_on_valley_*'",
                            /*plots=*/false);
  app.add_option("--config", config_source, "configuration: a preset (" + game::preset_list() + ") or a JSON file")
      ->capture_default_str();
  app.add_option("--eval-maps", eval_maps, "maps to evaluate the trained policies on")->delimiter(',')->capture_default_str();

  return cli::experiment_main(app, argc, argv, o, [&]() -> std::unique_ptr<experiment::Experiment> {
    const auto config = cli::config_or_listing(config_source, o);
    if (!config) return nullptr;
    const auto train = cli::load_arena(o.map, !o.no_cache);
    std::vector<std::shared_ptr<const world::Arena>> evals;
    for (const auto& m : eval_maps) evals.push_back(cli::load_arena(m, !o.no_cache));
    return std::make_unique<experiment::GeneralizeExperiment>(train, std::move(evals), *config,
                                                              experiment::GeneralizeSettings{.sweep = o.sweep});
  });
}
