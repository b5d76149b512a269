#pragma once
// The files experiments write (docs/results.md). Every writer goes through AtomicFile, so a file is either
// complete or absent.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "game/episode.hpp"
#include "results/csv_writer.hpp"
#include "world/arena.hpp"

namespace peg3d::results {

/// One run of a sweep: its identity and its greedy evaluation after training.
struct RunRecord {
  std::string scenario;
  std::string algorithm;
  int repeat = 0;
  std::uint64_t seed = 0;
  game::EpisodeResult evaluation;
  int train_captures = 0;
};

/// The columns every per-episode CSV ends with (docs/results.md): outcome, captured, capture_time_s,
/// episode_time_s, final_distance_m, pursuer_path_m, evader_path_m, collisions, evader_pinned_fraction,
/// pursuer_pinned_fraction, pursuer_return, evader_return.
std::vector<std::string> with_episode_columns(std::vector<std::string> leading);

/// Appends one episode's cells, in the order of with_episode_columns().
void add_episode_cells(CsvWriter::Row& row, const game::EpisodeResult& e);

/// runs.csv: one row per record, in the given order.
void write_runs_csv(const std::filesystem::path& file, const std::vector<RunRecord>& runs);

/// The training episodes of one run, each with the classic opponent it was played against.
struct LearningCurve {
  std::vector<game::EpisodeResult> episodes;
  /// per episode: the policy name of the opponent-pool opponent (experiment/training.hpp), "" for co-learning
  std::vector<std::string> pool_opponents;
};

/// learning_curves.csv: `curves[i]` holds the training episodes of `runs[i]`.
void write_learning_curves_csv(const std::filesystem::path& file, const std::vector<RunRecord>& runs,
                               const std::vector<LearningCurve>& curves);

/// `folder / (name + extension)` for a name made of map-given parts (scenario names): throws InputError when
/// the name could leave the folder or hide a file (see world::is_safe_name; '_' joins the parts).
std::filesystem::path output_file(const std::filesystem::path& folder, const std::string& name, const char* extension);

/// Pretty-printed JSON, atomically.
void write_json(const std::filesystem::path& file, const nlohmann::json& value);
void write_json(const std::filesystem::path& file, const nlohmann::ordered_json& value);

/// The arena's box, obstacles, terrain triangles and scenarios (map.json).
nlohmann::json map_to_json(const world::Arena& arena);

/// The Apollonius surfaces for each ratio a = vE / vP and both motion cones for P and E (apollonius.json and
/// `peg-apollonius --json`). `ratios` are shown in order; vP and vE give the cones.
nlohmann::json apollonius_to_json(const Vec3& pursuer, const Vec3& evader, double pursuer_speed, double evader_speed,
                                  const std::vector<double>& ratios);

}  // namespace peg3d::results
