#pragma once
// Trajectory files (docs/results.md, "trajectories/*.csv"): every recorded instant of one episode, one row
// per frame. Written by the experiments; read back by peg-view to replay an episode in the browser viewer.

#include <filesystem>

#include "game/episode.hpp"

namespace peg3d::results {

/// Largest trajectory file read back: a row of two agents takes about 700 bytes, so 100 000 steps of a
/// one-against-one game take about 70 MB.
inline constexpr std::size_t kMaxTrajectoryFileBytes = std::size_t{1} << 30;

/// Writes every frame of `trace`. Agents are labelled by game::agent_label.
void write_trajectory_csv(const std::filesystem::path& file, const game::Trace& trace);

/// Reads a trajectory file back into a trace: times, every agent's position, heading, percept (the nearest
/// obstacle's point rebuilt from its distance and angle errors), command, reward and activity; collisions
/// (kind and frame; the agent's position stands for the contact point) and captures (by the nearest
/// pursuer, as the game picks it). Files written before the `_active`, `_hit` and `_captured` columns
/// existed read as every agent active, no collision, and a capture wherever an evader leaves the game.
/// Throws InputError naming the file, line and column.
game::Trace read_trajectory_csv(const std::filesystem::path& file);

}  // namespace peg3d::results
