// peg-matchup: every pursuer policy against every evader policy on a map, N seeds per scenario, every agent of
// a role playing the same policy (teams too: maps/pack.yaml). The FACL agents are trained per scenario and
// seed (or loaded with --pursuer-policy / --evader-policy).
#include <cstdio>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "core/config_json.hpp"
#include "experiment/matchup_experiment.hpp"
#include "game/config_file.hpp"
#include "game/saved_policy.hpp"
#include "results/result_files.hpp"
#include "results/run_info.hpp"
#include "sweep/progress_reporter.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-matchup: every pursuer policy against every evader policy"};
  cli::SweepOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/matchup";
  o.sweep.repeats = 10;
  std::vector<std::string> pursuers{"facl", "pure-pursuit", "pn", "apollonius"};
  std::vector<std::string> evaders{"facl", "flee", "flee-apollonius", "random"};
  std::string config_source = "peg3d";
  std::filesystem::path pursuer_policy, evader_policy;
  bool list_config = false;
  std::vector<std::string> html;
  cli::add_sweep_options(app, o);
  cli::add_html_option(app, html, "SCENARIO_rREPEAT_PURSUER_vs_EVADER, e.g. S1_r0_pn_vs_flee or 'S2_r0_*'");
  app.add_option("--config", config_source,
                 "configuration the agents start from: a preset (" + game::preset_list() + ") or a JSON file")
      ->capture_default_str();
  app.add_option("--pursuers", pursuers, "pursuer policies: facl, pure-pursuit, pn, apollonius, random")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--evaders", evaders, "evader policies: facl, flee, flee-apollonius, random")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--pursuer-policy", pursuer_policy, "use this saved pursuer (FACL or MLP) in the facl slot instead of training one");
  app.add_option("--evader-policy", evader_policy, "use this saved evader (FACL or MLP) in the facl slot instead of training one");
  app.add_flag("--list-config", list_config, "print every configuration field and exit");

  return cli::sweep_main(app, argc, argv, [&] {
    const game::GameConfig config = game::apply_game_overrides(game::load_game_config(config_source), o.sets);
    if (list_config) {
      std::fputs(config::format_field_list(config::list_fields(config)).c_str(), stdout);
      return 0;
    }
    experiment::MatchupSettings s;
    s.pursuers.clear();
    s.evaders.clear();
    for (const auto& p : pursuers) s.pursuers.push_back(game::policy_named(p, game::Role::kPursuer, "--pursuers"));
    for (const auto& e : evaders) s.evaders.push_back(game::policy_named(e, game::Role::kEvader, "--evaders"));
    if (!pursuer_policy.empty()) s.pursuer_policy = game::load_saved_policy(pursuer_policy, game::Role::kPursuer);
    if (!evader_policy.empty()) s.evader_policy = game::load_saved_policy(evader_policy, game::Role::kEvader);
    s.sweep = o.sweep;
    if (!html.empty()) s.keep_trace = [&](const std::string& key) { return cli::chosen_for_html(html, key); };
    const auto arena = cli::load_arena(o.map, !o.no_cache);
    // Every pairing's Sim checks the map's starts against its agents before any run.
    const std::vector<game::Sim> sims = experiment::make_matchup_sims(arena, config, s);
    s.pool = std::make_shared<const experiment::OpponentPool>(arena, config);
    const std::size_t jobs = experiment::matchup_run_count(*arena, s);
    // The journal records every finished run; --resume reads it back and runs only the missing ones.
    const nlohmann::json setup = experiment::matchup_setup(*arena, config, s);
    cli::SweepSession session = cli::open_sweep(
        o, jobs, static_cast<std::size_t>(o.sweep.episodes) + 1 + s.pursuers.size() * s.evaders.size(), setup);
    s.sweep.control = session.control;
    const auto records = cli::run_stoppable(session, [&] { return experiment::run_matchups(sims, s); });
    if (!session.root()) return 0;  // the root writes the results
    const auto summary = experiment::summarize_matchups(records, s);
    experiment::write_matchups_csv(o.out / "matchups.csv", records);
    experiment::write_matchup_agents_csv(o.out / "agents.csv", records);
    results::write_json(o.out / "summary.json", summary);
    results::write_run_info(o.out / "run_info.json", "matchup", {{"map", arena.get()}},
                               {{"setup", setup}, {"seeds", experiment::matchup_seeds(*arena, s)}});
    session.complete();  // the files above hold every run
    std::vector<std::string> viewers;
    if (!html.empty()) {
      const view::ReplayScene scene(*arena);
      for (const auto& r : records) {
        if (!r.trace) continue;
        std::size_t p = 0, e = 0;  // the pairing's Sim: sims[1 + p * evaders + e]
        while (experiment::matchup_policy_name(s, game::Role::kPursuer, s.pursuers[p]) != r.pursuer) ++p;
        while (experiment::matchup_policy_name(s, game::Role::kEvader, s.evaders[e]) != r.evader) ++e;
        const std::filesystem::path file = results::output_file(o.out, experiment::matchup_key(r), ".html");
        cli::write_viewer(file, scene, sims[1 + p * s.evaders.size() + e], *r.trace,
                          {fmt::format("{} {} repeat {}: {} vs {}", arena->map().name, r.scenario, r.repeat, r.pursuer, r.evader),
                           fmt::format("peg-matchup, seed {}; {}", o.sweep.seed, cli::ending_of(r.result))});
        viewers.push_back(file.string());
      }
    }
    std::fputs(experiment::matchup_table(summary).c_str(), stdout);
    std::printf("\nresults in %s\n", o.out.string().c_str());
    cli::report_viewers(viewers, html);
    return 0;
  });
}
