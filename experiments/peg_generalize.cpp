// peg-generalize: train FACL pairs on one map, freeze them, and evaluate them on other maps (one with
// terrain among them); capture and collision rates per evaluation map.
#include <cstdio>

#include "cli_common.hpp"
#include "experiment/generalize_experiment.hpp"
#include "experiment/paper_experiment.hpp"
#include "experiment/progress_reporter.hpp"
#include "experiment/result_files.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-generalize: train on one map, evaluate the saved policies on others"};
  cli::SweepOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/generalize";
  o.repeats = 5;
  std::string config_name = "peg3d";
  std::vector<std::filesystem::path> eval_maps{"maps/paper.yaml", "maps/forest.yaml", "maps/valley.yaml"};
  cli::add_sweep_options(app, o);
  app.add_option("--config", config_name, "named configuration (peg3d, paper, baseline)")->capture_default_str();
  app.add_option("--eval-maps", eval_maps, "maps to evaluate the trained policies on")->delimiter(',')->capture_default_str();

  return cli::guarded_main(app, argc, argv, [&] {
    const game::GameConfig config = experiment::apply_game_overrides(game::preset(config_name), o.sets);
    const auto train = cli::load_arena(o.map, !o.no_cache);
    std::vector<std::shared_ptr<const world::Arena>> evals;
    std::vector<std::string> names;
    for (const auto& m : eval_maps) {
      evals.push_back(cli::load_arena(m, !o.no_cache));
      names.push_back(evals.back()->map().name.empty() ? m.stem().string() : evals.back()->map().name);
      for (const auto& sc : evals.back()->map().scenarios) game::Game(evals.back(), config).start(sc, 0);
    }
    for (const auto& sc : train->map().scenarios) game::Game(train, config).start(sc, 0);
    cli::prepare_output_dir(o.out);

    experiment::GeneralizeSettings s{o.seed, o.episodes, o.repeats, o.threads};
    std::size_t eval_count = 0;
    for (const auto& e : evals) eval_count += e->map().scenarios.size();
    const std::size_t jobs = train->map().scenarios.size() * o.repeats;
    experiment::ProgressReporter progress(jobs, jobs * (o.episodes + 1 + eval_count), stderr, o.plain_progress);
    std::vector<std::pair<std::string, std::unique_ptr<game::Policy>>> policies;
    const auto records = experiment::run_generalization(train, evals, config, s, &progress, &policies);
    progress.finish();
    const auto summary = experiment::summarize_generalization(records, names);
    std::filesystem::create_directories(o.out / "policies");
    for (const auto& [key, policy] : policies) experiment::save_policy(o.out / "policies" / (key + ".json"), *policy);
    experiment::write_generalization_csv(o.out / "generalization.csv", records);
    experiment::write_json(o.out / "summary.json", summary);
    std::printf("trained on %s (%zu scenarios x %d repeats, %d episodes each)\n", o.map.string().c_str(),
                train->map().scenarios.size(), o.repeats, o.episodes);
    std::fputs(experiment::generalization_table(summary).c_str(), stdout);
    std::printf("\nresults in %s\n", o.out.string().c_str());
    return 0;
  });
}
