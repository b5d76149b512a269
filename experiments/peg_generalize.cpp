// peg-generalize: train FACL agents on one map, freeze them, and evaluate them on other maps (one with
// terrain among them); capture and collision rates per evaluation map.
#include <cstdio>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "core/config_json.hpp"
#include "experiment/generalize_experiment.hpp"
#include "game/config_file.hpp"
#include "game/policy_io.hpp"
#include "results/result_files.hpp"
#include "results/run_info.hpp"
#include "sweep/progress_reporter.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-generalize: train on one map, evaluate the saved policies on others"};
  cli::SweepOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/generalize";
  o.sweep.repeats = 5;
  std::string config_source = "peg3d";
  std::vector<std::filesystem::path> eval_maps{"maps/paper.yaml", "maps/forest.yaml", "maps/valley.yaml"};
  bool list_config = false;
  std::vector<std::string> html;
  cli::add_sweep_options(app, o);
  cli::add_html_option(app, html, "TRAIN_rREPEAT_on_EVALMAP_EVALSCENARIO, e.g. S1_r0_on_forest_S2 or '*_r0_on_valley_*'");
  app.add_option("--config", config_source, "configuration: a preset (" + game::preset_list() + ") or a JSON file")
      ->capture_default_str();
  app.add_option("--eval-maps", eval_maps, "maps to evaluate the trained policies on")->delimiter(',')->capture_default_str();
  app.add_flag("--list-config", list_config, "print every configuration field and exit");

  return cli::sweep_main(app, argc, argv, [&] {
    const game::GameConfig config = game::apply_game_overrides(game::load_game_config(config_source), o.sets);
    if (list_config) {
      std::fputs(config::format_field_list(config::list_fields(config)).c_str(), stdout);
      return 0;
    }
    const auto train = cli::load_arena(o.map, !o.no_cache);
    std::vector<std::shared_ptr<const world::Arena>> arenas;
    for (const auto& m : eval_maps) arenas.push_back(cli::load_arena(m, !o.no_cache));
    const std::vector<std::string> names = experiment::eval_map_names(arenas);
    // Each Sim checks its map's starts against the agents before any run.
    const game::Sim train_sim(train, config);
    std::vector<experiment::EvalMap> evals;
    for (std::size_t m = 0; m < arenas.size(); ++m) evals.push_back({names[m], game::Sim(arenas[m], config)});

    experiment::GeneralizeSettings s{.sweep = o.sweep};
    s.pool = std::make_shared<const experiment::OpponentPool>(train, config);
    const std::size_t jobs = experiment::generalize_run_count(train_sim, s);
    // The journal records every finished run; --resume reads it back and runs only the missing ones.
    const nlohmann::json setup = experiment::generalize_setup(train_sim, evals, s);
    std::size_t eval_count = 0;
    for (const auto& e : arenas) eval_count += e->map().scenarios.size();
    cli::SweepSession session = cli::open_sweep(o, jobs, static_cast<std::size_t>(o.sweep.episodes) + 1 + eval_count, setup);
    s.sweep.control = session.control;
    if (!html.empty()) s.keep_trace = [&](const std::string& key) { return cli::chosen_for_html(html, key); };

    std::vector<std::pair<std::string, std::shared_ptr<const game::FaclModel>>> policies;
    const auto records =
        cli::run_stoppable(session, [&] { return experiment::run_generalization(train_sim, evals, s, &policies); });
    if (!session.root()) return 0;  // the root writes the results
    const auto summary = experiment::summarize_generalization(records, names);
    std::filesystem::create_directories(o.out / "policies");
    for (const auto& [key, model] : policies) {
      game::save_policy(results::output_file(o.out / "policies", key, ".json"), *model);
    }
    experiment::write_generalization_csv(o.out / "generalization.csv", records);
    results::write_json(o.out / "summary.json", summary);
    std::vector<std::pair<std::string, const world::Arena*>> maps{{"train", train.get()}};
    for (std::size_t m = 0; m < arenas.size(); ++m) maps.emplace_back("eval " + names[m], arenas[m].get());
    results::write_run_info(o.out / "run_info.json", "generalize", maps,
                            {{"setup", setup}, {"seeds", experiment::generalize_seeds(train_sim, s)}});
    session.complete();  // the files above hold every run
    std::vector<std::string> viewers;
    for (std::size_t m = 0; m < evals.size() && !html.empty(); ++m) {
      std::unique_ptr<view::ReplayScene> scene;
      for (const auto& r : records) {
        if (!r.trace || r.eval_map != evals[m].name) continue;
        if (!scene) scene = std::make_unique<view::ReplayScene>(evals[m].sim.arena());
        const std::filesystem::path file = results::output_file(o.out, experiment::generalize_key(r), ".html");
        cli::write_viewer(file, *scene, evals[m].sim, *r.trace,
                          {fmt::format("trained on {} {} (repeat {}), played on {} {}", train->map().name,
                                       r.train_scenario, r.repeat, r.eval_map, r.eval_scenario),
                           fmt::format("peg-generalize, seed {}, {} training episodes; {}", o.sweep.seed, o.sweep.episodes,
                                       cli::ending_of(r.result))});
        viewers.push_back(file.string());
      }
    }
    std::printf("trained on %s (%zu scenarios x %d repeats, %d episodes each)\n", o.map.string().c_str(),
                train->map().scenarios.size(), o.sweep.repeats, o.sweep.episodes);
    std::fputs(experiment::generalization_table(summary).c_str(), stdout);
    std::printf("\nresults in %s\n", o.out.string().c_str());
    cli::report_viewers(viewers, html);
    return 0;
  });
}
