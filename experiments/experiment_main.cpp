#include "experiment_main.hpp"

#include <chrono>
#include <cstdio>
#include <map>

#include <fmt/format.h>

#include "core/config_json.hpp"
#include "experiment/trial_config.hpp"
#include "players/registry.hpp"
#include "results/result_files.hpp"
#include "results/run_info.hpp"

namespace peg3d::cli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The viewer files of the recorded episodes the patterns choose, one scene per arena (built on first use).
std::vector<std::string> write_viewers(const experiment::Experiment& e, const ExperimentOptions& o) {
  std::vector<std::string> files;
  if (o.html.empty()) return files;
  std::map<const world::Arena*, std::unique_ptr<view::ReplayScene>> scenes;
  for (const experiment::RecordedEpisode& r : e.recorded()) {
    if (!key_chosen(o.html, r.key)) continue;
    auto& scene = scenes[&r.sim->arena()];
    if (!scene) scene = std::make_unique<view::ReplayScene>(r.sim->arena());
    const std::filesystem::path file = results::output_file(o.out, r.key, ".html");
    write_viewer(file, *scene, *r.sim, *r.trace, {r.title, r.subtitle});
    files.push_back(file.string());
  }
  return files;
}

}  // namespace

void add_experiment_flags(CLI::App& app, ExperimentOptions& o, const std::string& html_keys, bool plots) {
  add_sweep_options(app, o);
  if (!html_keys.empty()) add_html_option(app, o.html, html_keys);
  if (plots) app.add_flag("!--no-plots", o.plots, "skip the figures");
  app.add_flag("--list-config", o.list_config, "print every configuration field and exit");
  app.add_flag_callback(
      "--list-players",
      [] {
        std::fputs(players::player_listing().c_str(), stdout);
        throw CLI::Success();
      },
      "print every player (the values of --pursuers, --evaders and policy fields) and exit");
}

std::optional<std::vector<experiment::Algorithm>> algorithms_or_listing(const std::vector<std::string>& names,
                                                                        const ExperimentOptions& o) {
  std::vector<experiment::Algorithm> algorithms = experiment::make_algorithms(names, o.sets);
  if (!o.list_config) return algorithms;
  for (const auto& a : algorithms) fmt::print("# {}\n{}\n", a.name, config::format_field_list(config::list_fields(a.config)));
  return std::nullopt;
}

std::optional<experiment::TrialConfig> config_or_listing(const std::string& source, const ExperimentOptions& o) {
  experiment::TrialConfig config = experiment::load_trial_config(source, o.sets);
  if (!o.list_config) return config;
  std::fputs(config::format_field_list(config::list_fields(config)).c_str(), stdout);
  return std::nullopt;
}

int experiment_main(CLI::App& app, int argc, char** argv, const ExperimentOptions& o, const MakeExperiment& make) {
  return sweep_main(app, argc, argv, [&] {
    const auto start = std::chrono::steady_clock::now();
    const std::unique_ptr<experiment::Experiment> e = make();
    if (!e) return 0;
    if (!o.html.empty()) e->record_episodes([&o](const std::string& key) { return key_chosen(o.html, key); });
    // The journal records every finished run; --resume reads it back and runs only the missing ones.
    SweepSession session = open_sweep(o, e->run_count(), e->episodes_per_run(), e->setup());
    experiment::SweepTiming timing{.build_seconds = seconds_since(start),
                                   .threads = o.sweep.threads,
                                   .ranks = process_group() ? process_group()->size() : 1};
    const auto run_start = std::chrono::steady_clock::now();
    run_stoppable(session, [&] {
      experiment::run_experiment(*e, o.sweep.threads, session.control, session.root());
      return 0;
    });
    timing.run_seconds = seconds_since(run_start);
    if (!session.root()) return 0;  // the root writes the results

    // Nothing but the journal is written before every run has finished.
    e->write_results(o.out, timing);
    results::write_run_info(o.out / "run_info.json", e->kind(), e->maps(), e->run_info());
    session.complete();  // the files above hold every run
    if (o.plots && !e->plot_script().empty()) run_plot_script(e->plot_script(), o.out);
    const std::vector<std::string> viewers = write_viewers(*e, o);
    std::fputs(e->report(timing).c_str(), stdout);
    std::printf("\nresults in %s\n", o.out.string().c_str());
    report_viewers(viewers, o.html);
    return 0;
  });
}

}  // namespace peg3d::cli
