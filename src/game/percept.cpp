#include "game/percept.hpp"

#include <Eigen/Core>

namespace peg3d::game {
namespace {

// The nearest point of the arena boundary from an inside point, and its distance.
ObstacleSense nearest_boundary(const Vec3& p, const Box& arena) {
  ObstacleSense s;
  s.distance = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    for (const bool high : {false, true}) {
      const double d = high ? arena.hi[axis] - p[axis] : p[axis] - arena.lo[axis];
      if (d < s.distance) {
        s.distance = d;
        s.point = p;
        s.point[axis] = high ? arena.hi[axis] : arena.lo[axis];
      }
    }
  }
  s.distance = std::max(s.distance, 0.0);
  s.found = true;
  return s;
}

}  // namespace

Percept perceive(Role role, const ObservationConfig& observation, double radius, const KinematicState& self,
                 const KinematicState& other, const ObstacleSense& field, const Box& arena, double field_cap) {
  Percept out;
  const Vec3 to_other = other.position - self.position;
  out.target_distance = to_other.norm();
  // The pursuer aims along P->E. The paper measures the evader's angle from E->P; peg3d's default measures
  // it from P->E (away), so that fleeing reads 0 instead of sitting on the +-pi wrap.
  Vec3 reference = to_other;
  if (role == Role::kEvader && observation.evader_reference == EvaderReference::kAwayFromPursuer) {
    reference = -to_other;
  }
  if (out.target_distance > 0.0) out.target = angle_errors(self.heading, reference);
  // Both roles see the opponent's heading against the same line, P->E: an interceptor's lead and an evader's
  // turn away from straight flight both read as departures from 0.
  if (observation.opponent_heading && out.target_distance > 0.0) {
    out.opponent_heading = angle_errors(other.heading, role == Role::kPursuer ? to_other : Vec3(-to_other));
  }

  out.obstacle = field;
  if (observation.boundary_is_obstacle) {
    const ObstacleSense wall = nearest_boundary(self.position, arena);
    if (wall.distance < out.obstacle.distance && wall.distance <= field_cap) out.obstacle = wall;
  }
  const Vec3 to_obstacle = out.obstacle.point - self.position;
  if (out.obstacle.found && to_obstacle.squaredNorm() > 0.0) {
    out.to_obstacle = angle_errors(self.heading, to_obstacle);
  } else {
    out.to_obstacle = {kPi, 0.0};  // nothing in range reads as "behind"
  }
  out.pinned = is_pinned(self.position, radius, arena);
  return out;
}

}  // namespace peg3d::game
