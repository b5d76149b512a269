// peg-league: train FACL policies with one or more algorithms (each a configuration with its training
// procedure) over several seeds, then play every pursuer (trained and classic) against every evader (trained
// and scripted) on held-out evaluation seeds and maps, and write the cross-play matrix (docs/learning.md).
#include "experiment/league_experiment.hpp"
#include "experiment_main.hpp"
#include "players/registry.hpp"

using namespace peg3d;
using experiment::saved_entrant, experiment::league_maps;

int main(int argc, char** argv) {
  CLI::App app{"peg-league: trained FACL policies against each other and the classic strategies, across seeds and maps"};
  cli::ExperimentOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/league";
  o.sweep = experiment::LeagueSettings{}.sweep;
  experiment::LeagueSettings s;
  std::vector<std::string> algorithms{"peg3d", "robust"}, pursuers = s.classic_pursuers, evaders = s.classic_evaders,
                           pursuer_entrants, evader_entrants;
  std::vector<std::filesystem::path> eval_maps;
  std::string eval_heading = "random", train_heading = "random";
  const std::string headings = "random, chase, facing, plus-x";
  cli::add_experiment_flags(app, o, "", /*plots=*/true);
  app.remove_option(app.get_option("--repeats"));  // training seeds and evaluation seeds instead
  app.get_option("--map")->description("the map the policies train on (YAML, docs/maps.md)");
  app.get_option("--episodes")->description("training episodes per training run");
  const auto option = [&app](const char* flag, auto& value, const std::string& what) {
    return app.add_option(flag, value, what)->capture_default_str();
  };
  option("--algorithms", algorithms, "algorithms that train policies: presets (" + game::preset_list() + ")")->delimiter(',');
  option("--pursuers", pursuers,
         "classic pursuers in the league: " + players::player_names(game::Role::kPursuer, players::kNeedsTraining))->delimiter(',');
  option("--evaders", evaders,
         "scripted evaders in the league: " + players::player_names(game::Role::kEvader, players::kNeedsTraining))->delimiter(',');
  option("--eval-maps", eval_maps, "maps the games are played on (default: the training map)")->delimiter(',');
  option("--train-seeds", o.sweep.repeats, "training runs (seeds) per algorithm")->check(CLI::PositiveNumber);
  option("--eval-seeds", s.eval_seeds, "evaluation games per start and pairing (held-out seeds)")->check(CLI::PositiveNumber);
  option("--eval-heading", eval_heading, "initial headings of the evaluation games: " + headings);
  option("--train-heading", train_heading, "initial headings of training: " + headings + ", or config (each algorithm's)");
  option("--pursuer-entrant", pursuer_entrants, "a saved pursuer (FACL or MLP file) entering: NAME=FILE or FILE; repeatable");
  option("--evader-entrant", evader_entrants, "a saved evader entering the league: NAME=FILE or FILE; repeatable");

  return cli::experiment_main(app, argc, argv, o, [&]() -> std::unique_ptr<experiment::Experiment> {
    auto algs = cli::algorithms_or_listing(algorithms, o);
    if (!algs) return nullptr;
    s.classic_pursuers = experiment::classic_policies(pursuers, game::Role::kPursuer, "--pursuers");
    s.classic_evaders = experiment::classic_policies(evaders, game::Role::kEvader, "--evaders");
    s.eval_heading = *experiment::heading_named(eval_heading, "--eval-heading", false);
    s.train_heading = experiment::heading_named(train_heading, "--train-heading", true);
    for (const auto& e : pursuer_entrants) s.saved_pursuers.push_back(saved_entrant(e, game::Role::kPursuer, cli::resolve_input));
    for (const auto& e : evader_entrants) s.saved_evaders.push_back(saved_entrant(e, game::Role::kEvader, cli::resolve_input));
    s.sweep = o.sweep;
    const auto train = cli::load_arena(o.map, !o.no_cache);
    std::vector<std::shared_ptr<const world::Arena>> evals;
    for (const auto& m : eval_maps) evals.push_back(cli::load_arena(m, !o.no_cache));
    return std::make_unique<experiment::League>(train, league_maps(train, std::move(evals)), std::move(*algs), s);
  });
}
