#pragma once
// The league (docs/learning.md): FACL policies trained by one or more algorithms (a configuration each,
// with its training procedure) over several training seeds, then every pursuer (each trained one and the
// classic guidance laws) against every evader (each trained one and the scripted evaders) on evaluation
// maps, from every start of each map, over held-out evaluation seeds. Trained policies meet opponents of
// other seeds and other algorithms, not only the one they learned with.
//
// Training run (a, t): one lineup of algorithm a learns for `episodes` episodes, episode e from the training
// map's scenario e mod n (a policy that plays every start, not one per start), seeded derive_seed(root,
// {1, a, t}). Evaluation game: for each evaluation map m, scenario s and evaluation seed k, every pairing
// plays one greedy episode seeded derive_seed(root, {2, m, s, k}); the classic policies' own seeds derive
// from it by role only, so all pairings at one start are paired comparisons.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/algorithms.hpp"
#include "experiment/experiment.hpp"
#include "experiment/sweep_settings.hpp"
#include "experiment/training.hpp"
#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "players/lineup.hpp"
#include "players/registry.hpp"
#include "players/saved_policy.hpp"
#include "game/sim.hpp"
#include "results/result_files.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

/// A saved policy entering the league: it plays every game of its role, greedily, and trains nothing.
struct SavedEntrant {
  std::string name;  ///< its name in the results; unique among the entrants
  std::shared_ptr<const players::SavedPolicy> policy;
};

struct LeagueSettings {
  /// The classic players of each role (players/registry.hpp): by default the role's baselines.
  std::vector<std::string> classic_pursuers = players::baseline_players(game::Role::kPursuer);
  std::vector<std::string> classic_evaders = players::baseline_players(game::Role::kEvader);
  /// Root seed, training episodes per run (4000 by default; docs/learning.md: the robust evader needs 4000),
  /// repeats (the training runs, or seeds, per algorithm: --train-seeds, 3 by default), threads and control
  /// (the journal holds the training runs).
  SweepSettings sweep{.episodes = 4000, .repeats = 3};
  int eval_seeds = 5;  ///< evaluation games per start and pairing, >= 1
  /// Initial headings of the evaluation games: random by default, so that the evaluation seeds give different
  /// games even between deterministic policies.
  game::InitialHeading eval_heading = game::InitialHeading::kRandom;
  /// Initial headings of the training episodes, replacing the algorithms' initial_heading; nullopt keeps
  /// theirs. Random by default: the training starts as the games do (docs/learning.md).
  std::optional<game::InitialHeading> train_heading = game::InitialHeading::kRandom;
  /// Saved pursuers and evaders (FACL or MLP files) entering beside the trained and classic ones. A FACL file
  /// plays with the agent configuration it was saved with, an MLP with the rules' (the first algorithm's).
  std::vector<SavedEntrant> saved_pursuers, saved_evaders;
};

/// The classic pursuers or scripted evaders `names` names (players::player_named); a learning player (facl) is
/// refused, since the trained entrants come from the algorithms. Errors name `flag`.
std::vector<std::string> classic_policies(const std::vector<std::string>& names, game::Role role, const std::string& flag);

/// An initial heading by name (random, chase, facing, plus-x), or, when `config_allowed`, "config" (nullopt:
/// each algorithm's own). InvalidParameter naming `flag` otherwise.
std::optional<game::InitialHeading> heading_named(const std::string& name, const std::string& flag,
                                                  bool config_allowed);

/// A saved entrant from NAME=FILE, or FILE alone (named by its stem): the policy file resolve(FILE), loaded
/// for `role` (players::load_saved_policy).
SavedEntrant saved_entrant(const std::string& spec, game::Role role,
                           const std::function<std::filesystem::path(const std::filesystem::path&)>& resolve);

/// One player of the league.
struct Entrant {
  std::string name;   ///< "ALGORITHM#SEED" for a trained policy, the policy's name for a classic one
  std::string group;  ///< the algorithm's name (its training seeds pooled), or the classic policy's name
  game::Role role = game::Role::kPursuer;
  std::string policy{players::kFacl};  ///< its player: facl for trained and saved entrants
  int algorithm = -1;   ///< index of its algorithm (trained entrants), else -1
  int train_seed = -1;  ///< index of its training seed (trained entrants), else -1
  int saved = -1;       ///< index of its saved policy in the settings' list (saved entrants), else -1
};

/// The trained entrants first (algorithm-major, then training seed), then the classic ones, then the saved ones,
/// per role. An algorithm whose role is not played by FACL has no trained entrant of that role.
std::vector<Entrant> league_entrants(const std::vector<Algorithm>& algorithms, const LeagueSettings& settings,
                                     game::Role role);

/// An evaluation map and the name results give it.
struct LeagueMap {
  std::string name;
  std::shared_ptr<const world::Arena> arena;
};

/// The evaluation maps by name (eval_map_names); none: the training map alone.
std::vector<LeagueMap> league_maps(const std::shared_ptr<const world::Arena>& train,
                                   std::vector<std::shared_ptr<const world::Arena>> evals);

/// Everything a league plays, built (and every start checked against every configuration) before any run. As
/// an Experiment, its runs are the training runs (run a * train_seeds + t is algorithm a's seed t); once they
/// are in, the root plays every game (finish). Result files (docs/learning.md, written by league_report.cpp):
/// policies/, games.csv, learning_curves.csv, matrix.csv, matrix_entrants.csv, summary.json; the heat map by
/// tools/plot_league.py.
class League : public Experiment {
 public:
  League(std::shared_ptr<const world::Arena> train, std::vector<LeagueMap> eval_maps, std::vector<Algorithm> algorithms,
         LeagueSettings settings);

  const LeagueSettings& settings() const { return settings_; }
  LeagueSettings& settings() { return settings_; }
  const std::vector<Algorithm>& algorithms() const { return algorithms_; }
  const std::vector<LeagueMap>& eval_maps() const { return maps_; }
  const std::vector<Entrant>& pursuers() const { return pursuers_; }
  const std::vector<Entrant>& evaders() const { return evaders_; }
  const world::Arena& train_arena() const { return *train_; }

  /// Training runs (seeds) per algorithm.
  int train_seeds() const { return settings_.sweep.repeats; }
  std::size_t training_runs() const { return algorithms_.size() * static_cast<std::size_t>(train_seeds()); }
  /// The configuration the games of a pairing are played with (groups: the algorithms, then the classic policies
  /// of the role). Its rules are the first algorithm's; each algorithm's side brings its own agents and its
  /// opponent choice (team.pursuer_target or team.evader_threat).
  const game::GameConfig& game_config(std::size_t map, int pursuer_group, int evader_group) const {
    return sim_of(map, pursuer_group, evader_group).config();
  }
  /// Evaluation games in all: pursuers x evaders x starts of every evaluation map x evaluation seeds.
  std::size_t games() const;

  /// The journal header: experiment, build, map hashes, seeds, episodes, the algorithms' configurations.
  nlohmann::json setup() const override;

  /// One evaluation game.
  struct Game {
    std::string map, scenario;
    int eval_seed = 0;
    std::string pursuer, evader;  ///< entrant names
    game::EpisodeResult result;
  };
  /// Trains every (algorithm, seed) run (journaled, spread over ranks: run_experiment), then, on the root, plays
  /// every game. Returns the games in order: map, scenario, evaluation seed, pursuer, evader. Non-root ranks
  /// return an empty list once the training is done.
  std::vector<Game> run(bool root);
  /// The games, once run() or finish(true) has played them.
  const std::vector<Game>& played() const { return games_; }

  // Experiment
  std::string kind() const override { return "league"; }
  std::size_t run_count() const override { return training_runs(); }
  std::size_t episodes_per_run() const override;
  void begin(const sweep::SweepControl& control) override;
  void run_one(std::size_t i) override;
  nlohmann::json encode(std::size_t i) const override;
  void restore(std::size_t i, const nlohmann::json& record) override;
  void finish(bool root) override;
  void write_results(const std::filesystem::path& out, const SweepTiming& timing) const override;
  std::vector<std::pair<std::string, const world::Arena*>> maps() const override;
  nlohmann::ordered_json run_info() const override;
  std::string report(const SweepTiming& timing) const override;
  std::string plot_script() const override { return "plot_league.py"; }

  /// The trained models of run (algorithm a, training seed t), once run() has trained them.
  const players::RoleModels& models(int a, int t, game::Role role) const;
  /// The training episodes of run (algorithm a, training seed t) with their pool opponents, once run() has
  /// trained them.
  results::LearningCurve curve(int a, int t) const;

 private:
  /// One evaluation start: a map, one of its scenarios, an evaluation seed.
  struct Start {
    std::size_t map, scenario;
    int seed;
  };

  const game::Sim& sim_of(std::size_t map, int pursuer_group, int evader_group) const;
  /// The group an entrant plays in: its algorithm, or after the algorithms its classic policy, or after those its
  /// saved policy.
  int group_of(const Entrant& e) const;
  /// Every game, on this process: one job per (map, scenario, evaluation seed) plays every pairing.
  std::vector<Game> play_games() const;
  /// Every pairing's game at one start, into `games` (pursuer-major).
  void play_start(const Start& start, std::span<Game> games) const;

  std::shared_ptr<const world::Arena> train_;
  std::vector<LeagueMap> maps_;
  std::vector<Algorithm> algorithms_;
  LeagueSettings settings_;
  std::vector<Entrant> pursuers_, evaders_;
  std::vector<game::Sim> train_sims_;     ///< per algorithm
  std::vector<OpponentPool> pools_;       ///< per algorithm
  /// Per evaluation map, pursuer group and evader group (groups: algorithms, then classic policies, then saved
  /// policies per role).
  std::vector<game::Sim> eval_sims_;
  int pursuer_groups_ = 0, evader_groups_ = 0;
  std::vector<players::RoleModels> trained_pursuers_, trained_evaders_;  ///< per training run
  std::vector<TrainingResult> training_;  ///< per training run: its episodes and their pool entries
  std::vector<Game> games_;
};

}  // namespace peg3d::experiment
