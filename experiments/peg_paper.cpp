// peg-paper: the paper's experiment end to end. For every scenario of the map (S1..S4 on maps/paper.yaml)
// and every algorithm (peg3d's FACL, the paper's configuration, the Al-Mahbashi-style baseline), repeats of
// co-learning followed by a greedy evaluation; results, statistics and figures in --out (docs/results.md).
#include <chrono>
#include <cstdio>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "core/config_json.hpp"
#include "experiment/paper_experiment.hpp"
#include "game/policy_io.hpp"
#include "results/result_files.hpp"
#include "results/run_info.hpp"
#include "results/trajectory_file.hpp"
#include "sweep/progress_reporter.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-paper: the paper's four scenarios, FACL against the baseline, with statistics and figures"};
  cli::SweepOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/paper";
  std::vector<std::string> algorithms{"peg3d", "baseline", "paper"};
  bool plots = true, list_config = false;
  std::vector<std::string> html;
  cli::add_sweep_options(app, o);
  cli::add_html_option(app, html, "SCENARIO_ALGORITHM, e.g. S1_peg3d or '*_peg3d'; the evaluation episode of repeat 0");
  app.add_option("--algorithms", algorithms, "algorithms to compare: presets (peg3d, baseline, paper, robust)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_flag("!--no-plots", plots, "skip the figures");
  app.add_flag("--list-config", list_config, "print every configuration field of each algorithm and exit");

  return cli::sweep_main(app, argc, argv, [&] {
    const auto wall_start = std::chrono::steady_clock::now();
    const std::vector<experiment::Algorithm> algs = experiment::make_algorithms(algorithms, o.sets);
    if (list_config) {
      for (const auto& a : algs) fmt::print("# {}\n{}\n", a.name, config::format_field_list(config::list_fields(a.config)));
      return 0;
    }
    const auto arena = cli::load_arena(o.map, !o.no_cache);
    const auto& scenarios = arena->map().scenarios;
    // One Sim per algorithm; each checks every start against its agents' radii before any run.
    const std::vector<game::Sim> sims = experiment::make_sims(arena, algs);
    const std::vector<experiment::OpponentPool> pools = experiment::make_pools(arena, algs);
    experiment::PaperSettings settings{.sweep = o.sweep, .trace_repeat = 0};
    const std::size_t runs = experiment::paper_run_count(*arena, algs, settings);
    // The journal records every finished run; --resume reads it back and runs only the missing ones.
    cli::SweepSession session = cli::open_sweep(o, runs, static_cast<std::size_t>(o.sweep.episodes) + 1,
                                                experiment::paper_setup(*arena, algs, settings));
    settings.sweep.control = session.control;
    const double build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

    const auto run_start = std::chrono::steady_clock::now();
    experiment::PaperResults paper =
        cli::run_stoppable(session, [&] { return experiment::run_paper_experiment(algs, sims, pools, settings); });
    const double run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count();
    if (!session.root()) return 0;  // the root writes the results

    // Outputs: nothing but the journal is written before every run has finished.
    std::vector<std::string> scenario_names, algorithm_names;
    for (const auto& s : scenarios) scenario_names.push_back(s.name);
    nlohmann::ordered_json config{{"map", cli::resolve_input(o.map).string()},
                                  {"seed", o.sweep.seed},
                                  {"episodes", o.sweep.episodes},
                                  {"repeats", o.sweep.repeats},
                                  {"algorithms", nlohmann::ordered_json::object()}};
    for (const auto& a : algs) {
      algorithm_names.push_back(a.name);
      config["algorithms"][a.name] = nlohmann::ordered_json::parse(config::to_json(a.config).dump());
    }
    const double time_limit = algs.front().config.time_limit;
    const nlohmann::ordered_json summary = experiment::summarize(paper.runs, scenario_names, algorithm_names, time_limit);
    std::filesystem::create_directories(o.out / "trajectories");
    std::filesystem::create_directories(o.out / "policies");
    results::write_json(o.out / "config.json", config);
    results::write_runs_csv(o.out / "runs.csv", paper.runs);
    results::write_learning_curves_csv(o.out / "learning_curves.csv", paper.runs, paper.curves);
    results::write_json(o.out / "summary.json", summary);
    for (const auto& [key, trace] : paper.traces) {
      results::write_trajectory_csv(results::output_file(o.out / "trajectories", key, ".csv"), trace);
    }
    for (const auto& [key, model] : paper.policies) {
      game::save_policy(results::output_file(o.out / "policies", key, ".json"), *model);
    }
    results::write_json(o.out / "map.json", results::map_to_json(*arena));
    results::write_json(o.out / "apollonius.json",
                           results::apollonius_to_json({10, 10, 10}, {-10, -10, 10}, 1.1, 1.0, {0.5, 1.0, 2.0}));
    results::write_json(o.out / "timing.json", nlohmann::ordered_json{{"world_build_s", build_seconds},
                                                                         {"runs_s", run_seconds},
                                                                         {"runs", runs},
                                                                         {"steps", paper.steps},
                                                                         {"steps_per_second", paper.steps / run_seconds},
                                                                         {"threads", o.sweep.threads},
                                                                         {"ranks", cli::process_group() ? cli::process_group()->size() : 1},
                                                                         {"world_cache", arena->stats().cache_status}});
    results::write_run_info(o.out / "run_info.json", "paper", {{"map", arena.get()}},
                               experiment::paper_run_info(settings));
    session.complete();  // the files above hold every run
    if (plots) cli::run_plot_script("plot_paper.py", o.out);
    // Viewer files beside the figures, one per chosen evaluation episode (repeat 0, as the trajectories).
    std::vector<std::string> viewers;
    std::unique_ptr<view::ReplayScene> scene;
    for (const auto& sc : scenarios) {
      for (std::size_t a = 0; a < algs.size(); ++a) {
        const std::string key = sc.name + "_" + algs[a].name;
        const auto trace = paper.traces.find(key);
        if (trace == paper.traces.end() || !cli::chosen_for_html(html, key)) continue;
        if (!scene) scene = std::make_unique<view::ReplayScene>(*arena);
        const game::EpisodeResult* result = nullptr;
        for (const auto& r : paper.runs) {
          if (r.scenario == sc.name && r.algorithm == algs[a].name && r.repeat == 0) result = &r.evaluation;
        }
        const std::filesystem::path file = results::output_file(o.out, key, ".html");
        cli::write_viewer(file, *scene, sims[a], trace->second,
                          {fmt::format("{} {}: {}", arena->map().name, sc.name, algs[a].name),
                           fmt::format("peg-paper, seed {}, repeat 0 after {} training episodes; {}", o.sweep.seed, o.sweep.episodes,
                                       result ? cli::ending_of(*result) : std::string("evaluation"))});
        viewers.push_back(file.string());
      }
    }

    std::fputs(experiment::summary_table(summary).c_str(), stdout);
    std::printf("\n%zu runs, %lld steps in %.1f s (%.0f steps/s); results in %s\n", runs, paper.steps, run_seconds,
                paper.steps / run_seconds, o.out.string().c_str());
    cli::report_viewers(viewers, html);
    return 0;
  });
}
