#pragma once
// The golden log of a collision-regression case (docs/collision-tests.md): every collision in order, every
// capture, how the episode ended, every agent's and mover's final state and a hash of the whole trajectory, as
// plain text of one record per line, `key=value` fields, that reads well in a review's diff. parse_log reads
// it back; compare_logs lists what changed, field by field, for a reviewer.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "game/episode.hpp"
#include "geometry/pose.hpp"

namespace peg3d::regress {

struct LoggedEvent {
  int step = 0;
  double time = 0.0;         ///< s, time of impact
  std::string agent;         ///< label: pursuer_0, evader_0, pursuer_1, ... (game::agent_label)
  std::string hit;           ///< what it hit: "sphere:3", "cylinder:0", "mesh:1", "mover:2", "agent:evader_1"
  int triangle = -1;         ///< triangle of a mesh, else -1 (written "-")
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double penetration = 0.0;  ///< m
};

struct LoggedCapture {
  int step = 0;
  double time = 0.0;
  std::string pursuer, evader;  ///< labels
  double distance = 0.0;        ///< m
};

/// An agent touching a pushable body (push mode): not a collision.
struct LoggedPush {
  int step = 0;
  double time = 0.0;  ///< s
  std::string agent;  ///< label
  int mover = -1;     ///< the body, by index in the map's movers
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
};

struct LoggedAgent {
  std::string label;
  Vec3 position = Vec3::Zero();
  double alpha = 0.0, theta = 0.0;  ///< rad, final heading
  double path = 0.0;                ///< m travelled
  bool active = true;               ///< still in the game at the end
};

struct LoggedMover {
  int id = 0;
  std::string kind;  ///< sphere, cylinder, box
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
};

struct CollisionLog {
  std::string name;     ///< the case's name
  std::string outcome;  ///< capture, timeout, pursuer-collision, evader-collision
  int steps = 0;
  double time = 0.0;    ///< s at the end
  std::vector<LoggedEvent> events;
  std::vector<LoggedCapture> captures;
  std::vector<LoggedPush> pushes;  ///< push mode: every push, in order
  std::vector<LoggedAgent> agents;
  std::vector<LoggedMover> movers;
  std::uint64_t trajectory_hash = 0;  ///< every agent's position and heading at every step, bit for bit
};

/// How far numbers may differ and still match (docs/collision-tests.md). The same build reproduces every
/// number exactly; a change of a millimetre (or of the time a millimetre takes at the agents' speeds) is
/// reported.
struct Tolerances {
  double time = 1e-5;    ///< s
  double length = 1e-4;  ///< m: points, positions, paths, distances, penetrations
  double unit = 1e-4;    ///< normals (unit vectors), orientations (quaternion components)
  double angle = 1e-5;   ///< rad, headings
};

/// The log of a played episode: its trace (every instant, collisions, captures, pushes), the final state, and
/// the movers' poses at the end (null when the map has none; in push mode the dynamic bodies' come from the
/// state's own world, so the pushed bodies' final poses are logged).
CollisionLog make_log(const std::string& name, const game::Trace& trace, const game::SimState& final_state,
                      const world::MoverTimeline* movers);

/// The log as text.
std::string format_log(const CollisionLog& log);

/// Reads a log written by format_log. Throws InputError naming `file` and the line of a malformed record.
CollisionLog parse_log(std::string_view text, const std::filesystem::path& file);

/// What differs from `expected` to `actual`, one line each, e.g. "event 3: hit sphere:12 -> (none)",
/// "event 1: time 4.300000 s -> 4.400000 s". Event and capture identities and order compare exactly, numbers
/// within `tol`. The trajectory hash is compared only when `strict` (it changes with any last-bit difference
/// that moves no collision); otherwise a differing hash is listed in `notes`.
std::vector<std::string> compare_logs(const CollisionLog& expected, const CollisionLog& actual, const Tolerances& tol,
                                      bool strict, std::vector<std::string>* notes = nullptr);

}  // namespace peg3d::regress
