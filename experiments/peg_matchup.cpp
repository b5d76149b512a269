// peg-matchup: every pursuer policy against every evader policy on a map, N seeds per scenario. The FACL
// pair is trained per scenario and seed (or loaded with --pursuer-policy / --evader-policy).
#include <cstdio>

#include "cli_common.hpp"
#include "experiment/matchup_experiment.hpp"
#include "experiment/paper_experiment.hpp"
#include "experiment/progress_reporter.hpp"
#include "experiment/result_files.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-matchup: every pursuer policy against every evader policy"};
  cli::SweepOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/matchup";
  o.repeats = 10;
  experiment::MatchupSettings s;
  std::string config_name = "peg3d";
  std::filesystem::path pursuer_policy, evader_policy;
  cli::add_sweep_options(app, o);
  app.add_option("--config", config_name, "named configuration the agents start from (peg3d, paper, baseline)")
      ->capture_default_str();
  app.add_option("--pursuers", s.pursuers, "pursuer policies: facl, pure-pursuit, pn, apollonius, random")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--evaders", s.evaders, "evader policies: facl, flee, flee-apollonius, random")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--pursuer-policy", pursuer_policy, "use this saved FACL pursuer instead of training one")
      ->check(CLI::ExistingFile);
  app.add_option("--evader-policy", evader_policy, "use this saved FACL evader instead of training one")
      ->check(CLI::ExistingFile);

  return cli::guarded_main(app, argc, argv, [&] {
    const game::GameConfig config = experiment::apply_game_overrides(game::preset(config_name), o.sets);
    game::GameConfig check = config;
    for (const auto& p : s.pursuers) {
      check.pursuer.policy = p;
      check.validate();
    }
    for (const auto& e : s.evaders) {
      check.evader.policy = e;
      check.validate();
    }
    if (!pursuer_policy.empty()) {
      experiment::load_policy(pursuer_policy);  // fail early on a bad file
      s.pursuer_policy = pursuer_policy;
    }
    if (!evader_policy.empty()) {
      experiment::load_policy(evader_policy);
      s.evader_policy = evader_policy;
    }
    s.seed = o.seed;
    s.episodes = o.episodes;
    s.repeats = o.repeats;
    s.threads = o.threads;
    const auto arena = cli::load_arena(o.map, !o.no_cache);
    for (const auto& sc : arena->map().scenarios) game::Game(arena, config).start(sc, 0);
    cli::prepare_output_dir(o.out);

    const std::size_t jobs = arena->map().scenarios.size() * o.repeats;
    experiment::ProgressReporter progress(jobs, jobs * (o.episodes + 1 + s.pursuers.size() * s.evaders.size()), stderr,
                                          o.plain_progress);
    const auto records = experiment::run_matchups(arena, config, s, &progress);
    progress.finish();
    const auto summary = experiment::summarize_matchups(records, s);
    experiment::write_matchups_csv(o.out / "matchups.csv", records);
    experiment::write_json(o.out / "summary.json", summary);
    std::fputs(experiment::matchup_table(summary).c_str(), stdout);
    std::printf("\nresults in %s\n", o.out.string().c_str());
    return 0;
  });
}
