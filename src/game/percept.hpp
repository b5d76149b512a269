#pragma once
// What one agent senses at one instant (paper eq. 19-20, before any fuzzification): the distance and angle
// errors to its opponent and to the nearest obstacle. Angle errors are signed, so that steering by them
// turns the heading towards the direction (docs/paper-notes.md, "Observations").

#include "game/game_config.hpp"
#include "geometry/angles.hpp"
#include "geometry/kinematics.hpp"

namespace peg3d::game {

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

/// Builds the percept of `role` from both kinematic states, the world's nearest obstacle at the agent's
/// position, and the arena box. Pure and allocation-free.
Percept perceive(Role role, const AgentConfig& self_config, const KinematicState& self, const KinematicState& other,
                 const ObstacleSense& field, const Box& arena, double field_cap);

/// Whether a centre is pinned: within max(radius, 0.1 m) of a face of the arena box.
inline bool is_pinned(const Vec3& p, double radius, const Box& arena) {
  return arena.inner_distance(p) <= std::max(radius, 0.1) + 1e-9;
}

}  // namespace peg3d::game
