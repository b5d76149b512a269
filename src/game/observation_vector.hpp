#pragma once
// The observation vector of the Python front (env/batch.hpp, docs/python.md) as far as one agent's view
// holds it: the 20 entries every learner outside the C++ side sees, and what an MLP policy trained there
// reads back on the C++ side (players/mlp_policy.hpp). The neighbour slots that follow need the whole state and
// are the batch's. kObservationEntries declares each entry once (name, unit, meaning, what bounds it); the
// batch's bounds, the Python package's names (peg3d.OBSERVATION) and the replay viewer's labels come from it.

#include <array>
#include <utility>

#include "game/policy.hpp"

namespace peg3d::game {

/// Entries of observation_base.
inline constexpr int kObservationBase = 20;

/// What bounds an entry, given the arena and the game (observation_bounds).
enum class EntryRange {
  kDistance,   ///< [0, reach]: reach the larger of the arena's diagonal and the distance field's cap
  kAngle,      ///< [-pi, pi]
  kPolar,      ///< [0, pi]
  kPositionX,  ///< the arena's extent along x (then y, z)
  kPositionY,
  kPositionZ,
  kOffsetX,    ///< +- the arena's size along x (then y, z): one point of the arena minus another
  kOffsetY,
  kOffsetZ,
  kVelocity,   ///< +- the fastest agent's speed
  kReach,      ///< +- reach
};

struct ObservationEntry {
  const char* name;     ///< as Python names it (peg3d.OBSERVATION)
  const char* unit;     ///< "m", "rad" or "m/s"
  const char* meaning;  ///< as the viewer and the docs say it
  EntryRange range;
};

/// The 20 entries observation_base writes, in order.
inline constexpr std::array<ObservationEntry, kObservationBase> kObservationEntries{{
    {"target_distance", "m", "d to opponent", EntryRange::kDistance},
    {"target_azimuth_error", "rad", "opponent azimuth error", EntryRange::kAngle},
    {"target_elevation_error", "rad", "opponent elevation error", EntryRange::kAngle},
    {"obstacle_distance", "m", "d to obstacle", EntryRange::kDistance},
    {"obstacle_azimuth_error", "rad", "obstacle azimuth error", EntryRange::kAngle},
    {"obstacle_elevation_error", "rad", "obstacle elevation error", EntryRange::kAngle},
    {"x", "m", "own position x", EntryRange::kPositionX},
    {"y", "m", "own position y", EntryRange::kPositionY},
    {"z", "m", "own position z", EntryRange::kPositionZ},
    {"alpha", "rad", "own heading azimuth", EntryRange::kAngle},
    {"theta", "rad", "own heading polar angle", EntryRange::kPolar},
    {"opponent_dx", "m", "opponent position minus own, x", EntryRange::kOffsetX},
    {"opponent_dy", "m", "opponent position minus own, y", EntryRange::kOffsetY},
    {"opponent_dz", "m", "opponent position minus own, z", EntryRange::kOffsetZ},
    {"opponent_vx", "m/s", "opponent velocity x", EntryRange::kVelocity},
    {"opponent_vy", "m/s", "opponent velocity y", EntryRange::kVelocity},
    {"opponent_vz", "m/s", "opponent velocity z", EntryRange::kVelocity},
    {"obstacle_dx", "m", "nearest obstacle point minus own position, x", EntryRange::kReach},
    {"obstacle_dy", "m", "nearest obstacle point minus own position, y", EntryRange::kReach},
    {"obstacle_dz", "m", "nearest obstacle point minus own position, z", EntryRange::kReach},
}};

/// The first entries: the percept, the paper's fuzzy inputs (eq. 19-20), as the viewer shows them.
inline constexpr int kPerceptEntries = 6;

/// The bounds of an entry of `range` on an arena of `box`, with `reach` (m) and the fastest agent's `speed`
/// (m/s).
std::pair<double, double> entry_bounds(EntryRange range, const Box& box, double reach, double speed);

/// Writes the view's 20 entries, float32, as kObservationEntries lists them:
///   [0]      d to the opponent, m                      the percept: the paper's fuzzy inputs (eq. 19-20)
///   [1, 2]   azimuth, elevation error to it, rad
///   [3]      d to the nearest obstacle, m (arena faces merged as configured)
///   [4, 5]   azimuth, elevation error to it, rad
///   [6..8]   own position, m
///   [9, 10]  own heading alpha, theta, rad
///   [11..13] opponent position minus own, m
///   [14..16] opponent velocity, m/s
///   [17..19] nearest obstacle point minus own position (movers included), m; 0 when none is in range
void observation_base(const AgentView& view, float* out);

}  // namespace peg3d::game
