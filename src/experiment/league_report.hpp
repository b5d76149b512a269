#pragma once
// What the league's games say (docs/learning.md): the cross-play matrix, the findings the issue asked for,
// and the league's result files.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/league_experiment.hpp"

namespace peg3d::experiment {

/// learning_curves.csv: one row per training episode of every run (algorithm, train_seed, episode, the
/// scenario it started from, pool_opponent, then the episode columns).
void write_league_learning_curves_csv(const std::filesystem::path& file, const League& league);

/// games.csv: one row per game (map, scenario, eval_seed, pursuer, evader, then the episode columns).
void write_league_games_csv(const std::filesystem::path& file, const std::vector<League::Game>& games);

/// The cross-play matrix, per pair of groups (trained entrants pooled over their training seeds) or of
/// entrants: games, capture rate with its Wilson interval, mean time to capture (captured games) and mean
/// evader survival time (every game, censored at the time limit) with t intervals, collision games, the
/// evader's mean pinned fraction.
nlohmann::ordered_json league_matrix(const League& league, const std::vector<League::Game>& games, bool by_group);
/// matrix.csv from league_matrix.
void write_league_matrix_csv(const std::filesystem::path& file, const nlohmann::ordered_json& matrix);

/// The questions, answered from the games: for each trained pursuer group, its capture rate against
/// each scripted evader beside the best classic pursuer's, and against the trained evaders of its own
/// group; for each trained evader group, its survival time against each classic pursuer beside the best
/// scripted evader's, paired by start and seed (paired t and Wilcoxon tests).
nlohmann::ordered_json league_findings(const League& league, const std::vector<League::Game>& games);

/// The matrix as an aligned text table (capture rate and mean survival).
std::string league_table(const nlohmann::ordered_json& matrix);

}  // namespace peg3d::experiment
