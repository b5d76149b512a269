#pragma once
// An agent's observation (issue 50): one table of segments (sense/segment.hpp) per agent, built once from the
// game's settings, and the one function that writes it, which the batch of the Python front (env/batch.hpp) and the
// C++ players of networks trained there (players/mlp_policy.hpp) share. The table, in order:
//   the 20 base entries (kObservationEntries: the percept, the agent's pose, its opponent's, its nearest obstacle),
//     one segment each;
//   k neighbour slots of the nearest other opponents, then k of the nearest teammates, still in the game, nearest
//     first: "neighbour.opponent.m.offset" (its position minus the agent's, m; with limited sight where the agent
//     takes it to be) and "neighbour.opponent.m.mask" (1, or 0 with zeros where there are fewer), likewise
//     "neighbour.teammate.m.*";
//   every segment of every sensor the agent carries, in the order it carries them (sense/sensors.hpp): the sight
//     sensor's "sight.visible" and "sight.age", the lidar's "lidar.ranges", ...
// Every entry's bounds hold what it can take on this Sim (the float bounds widened by one ulp each way). The
// Python package's names and offsets, the replay viewer's labels, docs/python.md's table and the policy files'
// record of what a network reads all come from this table.

#include <array>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "game/policy.hpp"
#include "sense/segment.hpp"

namespace peg3d::game {

class Sim;
class SimState;

/// Entries of observation_base.
inline constexpr int kObservationBase = 20;
/// The most neighbour slots of each kind (opponents, teammates) a table may have.
inline constexpr int kMaxNeighbours = 16;

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
  const char* name;     ///< its segment's name (peg3d.OBSERVATION)
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

/// An agent's observation: its segments, and where the game finds their values.
struct ObservationTable {
  std::vector<sense::Segment> segments;  ///< in order, tiling [0, size)
  int neighbours = 0;                    ///< k: the neighbour slots of each kind
  /// Where each sensor's segments lie: its index among the agent's sensors, and its entries [offset, offset + size).
  struct SensorPart {
    int sensor = 0;
    int offset = 0;
    int size = 0;
  };
  std::vector<SensorPart> sensors;
  int size() const { return sense::observation_size(segments); }
  /// The segment called `name`; null when there is none.
  const sense::Segment* find(std::string_view name) const;
};

/// The observation table of agent `rank` of `role` in `sim`, with `neighbours` slots of each kind (in [0,
/// kMaxNeighbours]).
ObservationTable observation_table(const Sim& sim, Role role, int rank, int neighbours);

/// The table of agent `rank` of `role` that reads what `recorded` (a policy file's segments: names, sizes and
/// units) lists: its own table with as many neighbour slots as `recorded` has. Throws std::invalid_argument with the
/// first segment that differs (sense::first_difference) when the agent's observation does not hold them.
ObservationTable bind_observation(const Sim& sim, Role role, int rank, std::span<const sense::Segment> recorded);

/// Writes agent i's observation in `state` as `table` (its own, or one bound to it) lays it out, float32, into
/// `out` (table.size() long). No allocation.
void write_observation(const Sim& sim, const SimState& state, int i, const ObservationTable& table, std::span<float> out);

/// Gives `state` its ObservationWriter over `sim` (made by the first reset, then pointed at the Sim the reset plays):
/// what every view's `observation` points at.
void attach_observation_writer(const Sim& sim, SimState& state);

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
