#pragma once
// The sight sensor's settings (issue 39, docs/sight.md): opponents seen only in line of sight. The test itself is
// sense/line_of_sight.hpp; what an agent does with what it sees (its memory of sightings, their estimates, the
// sharing between teammates) is the game's knowledge of its opponents (game/sight.hpp).

#include <concepts>
#include <type_traits>

#include "core/config_fields.hpp"

namespace peg3d::sense {

/// What an agent with limited sight estimates an opponent it does not see now to be doing (SightConfig::estimate).
enum class SightEstimate {
  kLastSeen,       ///< where it was last seen, heading as it was
  kDeadReckoning,  ///< where it was last seen, moved on since at the velocity it had then (kept in the arena)
};
inline constexpr config::EnumNames<SightEstimate, 2> kSightEstimateNames{
    {{SightEstimate::kLastSeen, "last-seen"}, {SightEstimate::kDeadReckoning, "dead-reckoning"}}};

/// Opponents seen only in line of sight (issue 39, docs/sight.md). Off (the default): the agent knows every
/// opponent's state at every step, the paper's full information. On: after each step (and at the reset) the
/// agent looks at every opponent in the game; it sees one when the opponent's centre is within `range`, within
/// the field of view (the angle between the agent's heading and the line to that centre is at most fov / 2),
/// and a sight ray reaches the opponent's sphere before any terrain, obstacle or mover (sense/line_of_sight.hpp:
/// `points` rays; other agents do not hide it). Each agent remembers its latest sighting of each opponent
/// (position, heading, velocity, when); every agent starts knowing where each opponent starts. Its opponent
/// inputs (the percept, the motion space, the Python entries) come from the estimate built on that sighting;
/// its rewards still measure the true distance.
struct SightConfig {
  bool enabled = false;  ///< limited sight; false: full information (the default)
  double range = 100.0;  ///< m, in (0, 1000]: the farthest an opponent's centre can be seen
  double fov = 360.0;    ///< deg, in (0, 360]: the field of view's full angle about the heading (360: all round)
  int points = 5;        ///< sight rays per look at an opponent, in [1, 9]: its centre, then points of its rim
  SightEstimate estimate = SightEstimate::kLastSeen;  ///< what the inputs hold while the opponent is out of sight
  /// Teammates share sightings: every agent of the role with share on holds the newest sighting any of them
  /// has of each opponent, and sees what any of them sees.
  bool share = false;
  bool operator==(const SightConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, SightConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.flag("enabled", c.enabled, "opponents are seen only in line of sight (false: full information, the default)");
  v.number("range", c.range, Range::open_closed(0, 1000), "m", "the farthest an opponent's centre can be seen");
  v.number("fov", c.fov, Range::open_closed(0, 360), "deg",
           "the field of view's full angle about the heading, a cone (360: all round)");
  v.integer("points", c.points, 1, 9, "", "sight rays per look at an opponent: its centre, then points of its rim");
  v.choice("estimate", c.estimate, kSightEstimateNames,
           "an opponent out of sight is where it was last seen, or moved on at its velocity then (dead-reckoning)");
  v.flag("share", c.share, "teammates with share on pool their sightings");
}

}  // namespace peg3d::sense
