// peg-league: train FACL policies with one or more algorithms (each a configuration with its training
// procedure) over several seeds, then play every pursuer (trained and classic) against every evader (trained
// and scripted) on held-out evaluation seeds and maps, and write the cross-play matrix (docs/learning.md).
#include <cstdio>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "core/config_json.hpp"
#include "experiment/generalize_experiment.hpp"
#include "experiment/league_experiment.hpp"
#include "experiment/league_report.hpp"
#include "game/policy_io.hpp"
#include "results/result_files.hpp"
#include "results/run_info.hpp"
#include "sweep/progress_reporter.hpp"

using namespace peg3d;

int main(int argc, char** argv) {
  CLI::App app{"peg-league: trained FACL policies against each other and the classic strategies, across seeds and maps"};
  cli::SweepOptions o;
  o.map = "maps/paper.yaml";
  o.out = "results/league";
  o.sweep = experiment::LeagueSettings{}.sweep;
  std::vector<std::string> algorithms{"peg3d", "robust"};
  std::vector<std::filesystem::path> eval_maps;
  std::vector<std::string> pursuers{"pure-pursuit", "pn", "apollonius"};
  std::vector<std::string> evaders{"flee", "flee-apollonius", "random"};
  experiment::LeagueSettings s;
  std::string eval_heading = "random", train_heading = "random";
  bool plots = true, list_config = false;
  cli::add_sweep_options(app, o);
  app.remove_option(app.get_option("--repeats"));  // training seeds and evaluation seeds instead
  app.get_option("--map")->description("the map the policies train on (YAML, docs/maps.md)");
  app.get_option("--episodes")->description("training episodes per training run");
  app.add_option("--algorithms", algorithms, "algorithms that train policies: presets (" + game::preset_list() + ")")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--train-seeds", o.sweep.repeats, "training runs (seeds) per algorithm")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--eval-seeds", s.eval_seeds, "evaluation games per start and pairing (held-out seeds)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--eval-maps", eval_maps, "maps the games are played on (default: the training map)")->delimiter(',');
  app.add_option("--eval-heading", eval_heading, "initial headings of the evaluation games: random, chase, facing, plus-x")
      ->capture_default_str();
  app.add_option("--train-heading", train_heading,
                 "initial headings of the training episodes: random, chase, facing, plus-x, or config (each "
                 "algorithm's initial_heading)")
      ->capture_default_str();
  app.add_option("--pursuers", pursuers, "classic pursuers in the league: pure-pursuit, pn, apollonius, random")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--evaders", evaders, "scripted evaders in the league: flee, flee-apollonius, random")
      ->delimiter(',')
      ->capture_default_str();
  std::vector<std::string> pursuer_entrants, evader_entrants;
  app.add_option("--pursuer-entrant", pursuer_entrants,
                 "a saved pursuer (FACL or MLP policy file) entering the league: NAME=FILE, or FILE (named by its stem); "
                 "repeatable");
  app.add_option("--evader-entrant", evader_entrants, "a saved evader entering the league: NAME=FILE or FILE; repeatable");
  app.add_flag("!--no-plots", plots, "skip the heat-map figure");
  app.add_flag("--list-config", list_config, "print every configuration field of each algorithm and exit");

  return cli::sweep_main(app, argc, argv, [&] {
    std::vector<experiment::Algorithm> algs = experiment::make_algorithms(algorithms, o.sets);
    if (list_config) {
      for (const auto& a : algs) fmt::print("# {}\n{}\n", a.name, config::format_field_list(config::list_fields(a.config)));
      return 0;
    }
    s.classic_pursuers.clear();
    s.classic_evaders.clear();
    for (const auto& p : pursuers) {
      const auto kind = game::policy_named(p, game::Role::kPursuer, "--pursuers");
      if (kind == game::PolicyKind::kFacl) throw InputError("--pursuers: facl is not a classic pursuer (use --algorithms)");
      s.classic_pursuers.push_back(kind);
    }
    for (const auto& e : evaders) {
      const auto kind = game::policy_named(e, game::Role::kEvader, "--evaders");
      if (kind == game::PolicyKind::kFacl) throw InputError("--evaders: facl is not a scripted evader (use --algorithms)");
      s.classic_evaders.push_back(kind);
    }
    const auto* heading = config::enum_value(game::kInitialHeadingNames, eval_heading);
    if (heading == nullptr) {
      throw InvalidParameter("--eval-heading", "\"" + eval_heading + "\"", "must be random, chase, facing or plus-x");
    }
    s.eval_heading = *heading;
    if (train_heading == "config") {
      s.train_heading.reset();
    } else if (const auto* h = config::enum_value(game::kInitialHeadingNames, train_heading)) {
      s.train_heading = *h;
    } else {
      throw InvalidParameter("--train-heading", "\"" + train_heading + "\"", "must be random, chase, facing, plus-x or config");
    }
    const auto saved = [](const std::vector<std::string>& specs, game::Role role) {
      std::vector<experiment::SavedEntrant> out;
      for (const std::string& spec : specs) {
        const std::size_t eq = spec.find('=');
        const std::filesystem::path file = eq == std::string::npos ? spec : spec.substr(eq + 1);
        const std::string name = eq == std::string::npos ? file.stem().string() : spec.substr(0, eq);
        out.push_back({name, game::load_saved_policy(cli::resolve_input(file), role)});
      }
      return out;
    };
    s.saved_pursuers = saved(pursuer_entrants, game::Role::kPursuer);
    s.saved_evaders = saved(evader_entrants, game::Role::kEvader);
    s.sweep = o.sweep;
    const auto train = cli::load_arena(o.map, !o.no_cache);
    std::vector<std::shared_ptr<const world::Arena>> arenas;
    if (eval_maps.empty()) {
      arenas.push_back(train);
    } else {
      for (const auto& m : eval_maps) arenas.push_back(cli::load_arena(m, !o.no_cache));
    }
    const std::vector<std::string> names = experiment::eval_map_names(arenas);
    std::vector<experiment::LeagueMap> maps;
    for (std::size_t m = 0; m < arenas.size(); ++m) maps.push_back({names[m], arenas[m]});
    // Every Sim (training and each pairing on each map) checks its starts before any run.
    experiment::League league(train, std::move(maps), std::move(algs), s);
    const nlohmann::json setup = league.setup();
    const std::size_t episodes = league.training_runs() * static_cast<std::size_t>(o.sweep.episodes) + league.games();
    // Progress counts the training episodes and the games, spread over the training runs.
    const std::size_t runs = league.training_runs();
    cli::SweepSession session = cli::open_sweep(o, runs, (episodes + runs - 1) / runs, setup);
    league.settings().sweep.control = session.control;
    const auto games = cli::run_stoppable(session, [&] { return league.run(session.root()); });
    if (!session.root()) return 0;  // the root writes the results

    const auto matrix = experiment::league_matrix(league, games, /*by_group=*/true);
    const auto entrants = experiment::league_matrix(league, games, /*by_group=*/false);
    const auto findings = experiment::league_findings(league, games);
    std::filesystem::create_directories(o.out / "policies");
    for (std::size_t a = 0; a < league.algorithms().size(); ++a) {
      for (int t = 0; t < league.train_seeds(); ++t) {
        for (const game::Role role : {game::Role::kPursuer, game::Role::kEvader}) {
          const auto& models = league.models(static_cast<int>(a), t, role).models;
          for (std::size_t k = 0; k < models.size(); ++k) {
            const std::string key = fmt::format("{}_{}_{}{}", league.algorithms()[a].name, t, game::to_string(role),
                                                k == 0 ? std::string() : fmt::format("_{}", k));
            game::save_policy(results::output_file(o.out / "policies", key, ".json"), *models[k]);
          }
        }
      }
    }
    experiment::write_league_games_csv(o.out / "games.csv", games);
    experiment::write_league_learning_curves_csv(o.out / "learning_curves.csv", league);
    experiment::write_league_matrix_csv(o.out / "matrix.csv", matrix);
    experiment::write_league_matrix_csv(o.out / "matrix_entrants.csv", entrants);
    results::write_json(o.out / "summary.json",
                           nlohmann::ordered_json{{"matrix", matrix}, {"entrants", entrants}, {"findings", findings}});
    std::vector<std::pair<std::string, const world::Arena*>> run_maps{{"train", train.get()}};
    for (std::size_t m = 0; m < arenas.size(); ++m) run_maps.emplace_back("eval " + names[m], arenas[m].get());
    results::write_run_info(o.out / "run_info.json", "league", run_maps,
                               {{"setup", setup},
                                {"seeds", {{"root", o.sweep.seed},
                                           {"derivation", "training run (a, t) = derive_seed(root, {1, a, t}); game at "
                                                          "(map m, scenario s, evaluation seed k) = derive_seed(root, "
                                                          "{2, m, s, k}) for every pairing, its classic pursuers "
                                                          "derive_seed(game, {1}), scripted evaders derive_seed(game, {2})"}}}});
    session.complete();  // the files above hold every run
    if (plots) cli::run_plot_script("plot_league.py", o.out);
    std::fputs(experiment::league_table(matrix).c_str(), stdout);
    std::printf("\nresults in %s\n", o.out.string().c_str());
    return 0;
  });
}
