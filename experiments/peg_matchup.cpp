// peg-matchup: every pursuer policy against every evader policy on a map, N seeds per scenario, every agent of
// a role playing the same policy (teams too: maps/pack.yaml). The FACL agents are trained per scenario and
// seed (or loaded with --pursuer-policy / --evader-policy).
#include "experiment/matchup_experiment.hpp"
#include "experiment_main.hpp"
#include "players/registry.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-matchup: every pursuer policy against every evader policy"};
  cli::ExperimentOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/matchup";
  o.sweep.repeats = 10;
  std::vector<std::string> pursuers = experiment::default_players(game::Role::kPursuer);
  std::vector<std::string> evaders = experiment::default_players(game::Role::kEvader);
  std::string config_source = "peg3d";
  std::filesystem::path pursuer_policy, evader_policy;
  std::vector<std::string> save_maps;
  cli::add_experiment_flags(app, o, "SCENARIO_rREPEAT_PURSUER_vs_EVADER, e.g. S1_r0_pn_vs_flee or 'S2_r0_*'", false);
  app.add_option("--config", config_source, "the agents' configuration: a preset (" + game::preset_list() + ") or a JSON file")
      ->capture_default_str();
  app.add_option("--pursuers", pursuers, "pursuer players: " + players::player_names(game::Role::kPursuer) + " (--list-players)")
      ->delimiter(',')->capture_default_str();
  app.add_option("--evaders", evaders, "evader players: " + players::player_names(game::Role::kEvader) + " (--list-players)")
      ->delimiter(',')->capture_default_str();
  app.add_option("--pursuer-policy", pursuer_policy, "a saved pursuer (FACL or MLP) playing the facl slot, not trained");
  app.add_option("--evader-policy", evader_policy, "a saved evader (FACL or MLP) playing the facl slot, not trained");
  app.add_option("--save-maps", save_maps,
                 "write each sensing agent's own map at the end of each game whose key matches one of these shell "
                 "patterns (as --html), as OctoMap .bt files in OUT/maps/KEY_AGENT.bt")
      ->delimiter(',');

  return cli::experiment_main(app, argc, argv, o, [&]() -> std::unique_ptr<experiment::Experiment> {
    const auto config = cli::config_or_listing(config_source, o);
    if (!config) return nullptr;
    experiment::MatchupSettings s{.pursuers = {}, .evaders = {}, .sweep = o.sweep};
    for (const auto& p : pursuers) s.pursuers.emplace_back(players::player_named(p, game::Role::kPursuer, "--pursuers").name);
    for (const auto& e : evaders) s.evaders.emplace_back(players::player_named(e, game::Role::kEvader, "--evaders").name);
    if (!pursuer_policy.empty()) s.pursuer_policy = players::load_saved_policy(pursuer_policy, game::Role::kPursuer);
    if (!evader_policy.empty()) s.evader_policy = players::load_saved_policy(evader_policy, game::Role::kEvader);
    if (!save_maps.empty()) {
      s.maps_dir = std::filesystem::path(o.out) / "maps";  // made by the first run that writes a map
      s.keep_maps = [&save_maps](const std::string& key) { return cli::key_chosen(save_maps, key); };
    }
    return std::make_unique<experiment::MatchupExperiment>(cli::load_arena(o.map, !o.no_cache), *config,
                                                           std::move(s));
  });
}
