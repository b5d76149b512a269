#pragma once
// The obstacle guard's settings: which headings the constraint layer (game/constraints.hpp) excludes near an
// obstacle.

#include <concepts>
#include <type_traits>

#include "core/config_fields.hpp"

namespace peg3d::game {

/// A safety layer on top of any policy: near an obstacle of the map (and, with `faces`, the arena boundary),
/// headings that approach it are excluded, like the motion space excludes headings that lose ground. Within
/// `stop_distance` of the obstacle the heading may not approach it at all; between `stop_distance` and
/// `warn_distance` the excluded cone about the direction to the obstacle narrows linearly to nothing. As a
/// last resort, measured on the exact shapes rather than the distance field, no step ends nearer than the
/// radius plus kHoldMargin (game/constraints.hpp) to a static obstacle: an agent with the guard on does not
/// run into one.
struct ObstacleGuard {
  bool enabled = true;
  bool faces = false;          ///< the arena's floor, ceiling and walls are guarded against too (nearest of both)
  double stop_distance = 0.8;  ///< m, > 0; covers radius + one step + the distance field's voxel error
  double warn_distance = 2.0;  ///< m, > stop_distance
  /// m, in [0, stop_distance): the guard also keeps clear of a second obstacle, the one nearest to the point
  /// this far ahead along the guarded heading, once it is nearer than stop_distance (sliding past one trunk
  /// into the next). Shorter than stop_distance so that a point inside the obstacle still counts. 0: the
  /// nearest obstacle only.
  double look_ahead = 0.6;
  bool operator==(const ObstacleGuard&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, ObstacleGuard>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.flag("enabled", c.enabled, "exclude headings that approach a nearby obstacle of the map");
  v.flag("faces", c.faces, "the arena's floor, ceiling and walls count as obstacles of the guard (the nearer one is guarded)");
  v.number("stop_distance", c.stop_distance, Range::positive(), "m", "closer than this, no heading may approach it");
  v.number("warn_distance", c.warn_distance, Range::positive(), "m",
           "from here to stop_distance the excluded cone widens to a half-space");
  v.require(c.warn_distance > c.stop_distance, "warn_distance", c.warn_distance, "must be > guard.stop_distance");
  v.number("look_ahead", c.look_ahead, Range::non_negative(), "m",
           "also keep clear of the obstacle nearest to the point this far ahead once within stop_distance (0: off)");
  v.require(c.look_ahead < c.stop_distance, "look_ahead", c.look_ahead, "must be < guard.stop_distance");
}

}  // namespace peg3d::game
