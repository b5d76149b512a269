#pragma once
// Collision-regression cases (docs/collision-tests.md): a map and a motion, played headless on the game's
// step(), whose collisions are logged and compared with a golden log. A case is a folder holding case.yaml
// (its golden log is golden.log beside it), or a single NAME.yaml file (its golden log NAME.log beside it).
//
//   map: map.yaml                 the map, relative to the case
//   scenario: S1                  optional, a scenario of the map (default: its first)
//   config: peg3d                 optional, a preset or a JSON configuration file (relative to the case)
//   set: [collision=penalize]     optional, configuration overrides as with --set
//   seed: 1                       optional, the run's seed (default 1)
//   agents:                       optional, who drives which agent (the others play the configuration's policy)
//     pursuer_0: {commands: pursuer.commands}   timed steering commands (a file, or inline [[t, da, dt], ...])
//     evader_0: {waypoints: evader.waypoints}   waypoints flown at the agent's speed (file or [[x, y, z, t?]])
//     pursuer_1: {policy: pursuer.json}         a saved policy (FACL or MLP)
//     evader_1: {scripted: flee}                a scripted policy by name

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "regress/collision_log.hpp"

namespace peg3d::regress {

/// How one agent of a case is driven.
struct AgentDriver {
  enum class Kind { kCommands, kWaypoints, kPolicy, kScripted };
  /// pursuer_0, evader_1, ... (game::agent_label); cases written before issue 37 may say pursuer or evader
  /// (the only agent of its role) or pursuer0, evader1, ...
  std::string label;
  int line = 0;       ///< its line in the case file, for messages
  Kind kind = Kind::kCommands;
  std::vector<game::TimedCommand> commands;
  std::vector<game::Waypoint> waypoints;
  std::filesystem::path policy;  ///< a saved policy file (FACL or MLP)
  std::string scripted = "flee";  ///< a scripted player's name (players/registry.hpp)
};

struct CollisionCase {
  std::string name;               ///< the folder's (or file's) name
  std::filesystem::path file;     ///< case.yaml (or NAME.yaml)
  std::filesystem::path golden;   ///< golden.log (or NAME.log)
  std::filesystem::path map;      ///< absolute
  std::string scenario;           ///< empty: the map's first
  int scenario_line = 0;          ///< its line in the case file, for messages
  std::string config = "peg3d";   ///< preset name or absolute path of a JSON file
  std::vector<std::string> overrides;
  std::uint64_t seed = 1;
  std::vector<AgentDriver> drivers;
};

/// Reads a case (a folder with case.yaml, or a .yaml file). Throws InputError naming the file, line and field.
CollisionCase load_case(const std::filesystem::path& path);

/// The cases at `path`: the case itself, or every case among the folder's entries, sorted by name.
std::vector<std::filesystem::path> find_cases(const std::filesystem::path& path);

/// A case played: the model it was played on, every instant, and its log.
struct CasePlay {
  game::Sim sim;
  game::Trace trace;
  CollisionLog log;
};

/// Plays the case headless (greedy, no learning). Throws InputError for bad input (map, configuration,
/// policy files, unknown agent labels).
CasePlay play_case(const CollisionCase& c, bool use_cache = true);

/// play_case's log.
CollisionLog run_case(const CollisionCase& c, bool use_cache = true);

/// Timed steering commands, one per line: `time_s d_alpha_deg d_theta_deg` (the requested heading changes per
/// step from that time on); `#` starts a comment.
std::vector<game::TimedCommand> read_commands(const std::filesystem::path& file);
/// Waypoints, one per line: `x y z` (flown to after the one before is reached) or `x y z time_s` (the target
/// from that time on).
std::vector<game::Waypoint> read_waypoints(const std::filesystem::path& file);

/// The label of agent i (pursuers first) of a scenario, as logs and trajectories write it.
std::string scenario_label(const world::Scenario& s, int i);

}  // namespace peg3d::regress
