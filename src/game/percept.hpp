#pragma once
// What one agent senses at one instant (paper eq. 19-20, before any fuzzification): the distance and angle
// errors to its opponent and to the nearest obstacle. Angle errors are signed, so that steering by them
// turns the heading towards the direction (docs/paper-notes.md, "Observations").

#include <concepts>
#include <type_traits>

#include "core/config_fields.hpp"
#include "game/role.hpp"
#include "geometry/angles.hpp"
#include "geometry/kinematics.hpp"

namespace peg3d::game {

/// Which angle errors the observation carries.
enum class AngleInputs {
  kAzimuth,           ///< paper: one signed azimuth error per direction (target, obstacle)
  kAzimuthElevation,  ///< a signed azimuth and a signed elevation error per direction
};
inline constexpr config::EnumNames<AngleInputs, 2> kAngleInputNames{
    {{AngleInputs::kAzimuth, "azimuth"}, {AngleInputs::kAzimuthElevation, "azimuth-elevation"}}};

/// The line the evader's target angle is measured from.
enum class EvaderReference {
  kTowardPursuer,    ///< paper eq. (20): from E->P, so fleeing straight away reads +-pi (the wrap point)
  kAwayFromPursuer,  ///< from P->E, so fleeing straight away reads 0
};
inline constexpr config::EnumNames<EvaderReference, 2> kEvaderReferenceNames{
    {{EvaderReference::kTowardPursuer, "toward-pursuer"}, {EvaderReference::kAwayFromPursuer, "away-from-pursuer"}}};


/// Where an agent's nearest-obstacle inputs (d_O and its angles, the Python entries 3-5 and 17-19) and its
/// obstacle guard come from.
enum class ObstacleSource {
  kWorld,   ///< the world as it is: the map's distance field and the movers where they are (today's default)
  kOwnMap,  ///< the agent's own map built from its scans (AgentConfig::map): the nearest occupied cell
};
inline constexpr config::EnumNames<ObstacleSource, 2> kObstacleSourceNames{
    {{ObstacleSource::kWorld, "world"}, {ObstacleSource::kOwnMap, "own-map"}}};

struct ObservationConfig {
  AngleInputs angles = AngleInputs::kAzimuthElevation;
  EvaderReference evader_reference = EvaderReference::kAwayFromPursuer;
  bool boundary_is_obstacle = true;  ///< floor, ceiling and walls count in d_O, its direction and r_O
  /// The opponent's heading as an input: its signed azimuth (and, with azimuth-elevation, elevation) error
  /// from the opponent's heading to the line P->E. 0 when a pursuer heads straight at the evader or an evader
  /// flees straight away; an interceptor's lead shows as the pursuer's error. Adds one input per channel.
  bool opponent_heading = false;
  double target_range = 35.0;        ///< m, d_PE partition [0, target_range], > 0 (paper 35)
  double obstacle_range = 5.0;       ///< m, d_O partition [0, obstacle_range], > 0 (paper 35)
  int sets = 5;                      ///< triangular sets per input, in [2, 64] (paper 5)
  /// The nearest obstacle: the world's, or the agent's own map's (needs map.enabled). The arena's faces stay
  /// known to the agent either way (boundary_is_obstacle).
  ObstacleSource obstacles = ObstacleSource::kWorld;
  /// Limited sight's two entries as inputs of each FACL channel: whether the opponent is in sight now (two sets,
  /// at 0 and 1) and how old the sighting it steers by is (`sets` sets over [0, sight_age_range]). Without limited
  /// sight the opponent is always in sight, aged 0. Adds two inputs per channel.
  bool sight_inputs = false;
  double sight_age_range = 10.0;     ///< s, the sighting's age partition [0, sight_age_range], > 0
  bool operator==(const ObservationConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, ObservationConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.choice("angles", c.angles, kAngleInputNames,
           "angle errors observed: the azimuth only (the paper) or azimuth and elevation");
  v.choice("evader_reference", c.evader_reference, kEvaderReferenceNames,
           "line the evader's target angle is measured from (paper: toward-pursuer)");
  v.flag("boundary_is_obstacle", c.boundary_is_obstacle,
         "the arena's floor, ceiling and walls count as the nearest obstacle in d_O and r_O");
  v.flag("opponent_heading", c.opponent_heading,
         "the opponent's heading, as its angle errors to the line P->E, is one more input of each FACL channel");
  v.number("target_range", c.target_range, Range::positive(), "m", "d_PE is partitioned over [0, target_range] (paper 35)");
  v.number("obstacle_range", c.obstacle_range, Range::positive(), "m",
           "d_O is partitioned over [0, obstacle_range] (paper 35)");
  v.integer("sets", c.sets, 2, 64, "", "triangular fuzzy sets per input (paper 5)");
  v.choice("obstacles", c.obstacles, kObstacleSourceNames,
           "the nearest obstacle of the inputs and the guard: the world's, or the agent's own map's (needs map.enabled)");
  v.flag("sight_inputs", c.sight_inputs,
         "whether the opponent is in sight and how old its sighting is are two more inputs of each FACL channel");
  v.number("sight_age_range", c.sight_age_range, Range::positive(), "s",
           "the sighting's age is partitioned over [0, sight_age_range] (sight_inputs)");
}

/// Nearest obstacle as the world reports it (distance capped, point valid only when found).
struct ObstacleSense {
  double distance = 0.0;         ///< m, capped at the field's maximum distance
  Vec3 point = Vec3::Zero();     ///< m, nearest occupied point when found
  bool found = false;            ///< false when nothing is within the cap
};

struct Percept {
  double target_distance = 0.0;  ///< d_PE, m
  AngleErrors target;            ///< rad, from the heading to the reference line (E->P or P->E for the evader)
  ObstacleSense obstacle;        ///< the nearest obstacle after merging the arena boundary when configured
  AngleErrors to_obstacle;       ///< rad, from the heading to the obstacle; (pi, 0) when none is in range
  AngleErrors opponent_heading;  ///< rad, from the opponent's heading to the line P->E; only with
                                 ///< observation.opponent_heading (else 0, 0)
  bool pinned = false;           ///< centre within max(radius, 0.1 m) of the floor, ceiling or a wall
};

/// Builds the percept of `role` (an agent of `radius`, m, observing as `observation` says) from both kinematic
/// states, the world's nearest obstacle at the agent's position, and the arena box. Pure and allocation-free.
Percept perceive(Role role, const ObservationConfig& observation, double radius, const KinematicState& self,
                 const KinematicState& other, const ObstacleSense& field, const Box& arena, double field_cap);

/// Whether a centre is pinned: within max(radius, 0.1 m) of a face of the arena box.
inline bool is_pinned(const Vec3& p, double radius, const Box& arena) {
  return arena.inner_distance(p) <= std::max(radius, 0.1) + 1e-9;
}

}  // namespace peg3d::game
