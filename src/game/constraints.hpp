#pragma once
// The constraint layer between what a policy asks for and how an agent moves, applied in this order:
//   bounded steering   the requested heading change is clamped to the steering bound and the climb limit
//   motion space       the paper's optimal motion space (section 3.1): a cone of headings about the line of sight
//   obstacle guard     headings that approach a nearby obstacle of the map are excluded (it outranks the motion space)
//   arena clamp        the agent moves along the heading and is clamped into the arena (kinematics advance())
// Each is a free function over plain data, tested on its own; constrained_heading() composes the first three.

#include <optional>
#include <span>

#include "game/game_config.hpp"
#include "game/percept.hpp"
#include "geometry/motion_cone.hpp"
#include "world/collision/collision_world.hpp"

namespace peg3d::game {

/// The heading after steering by u within the agent's bound for one sample of dt and its climb limit.
Heading bounded_steer(const Heading& h, const Steering& u, const SteeringConfig& steering, double dt);

/// The paper's optimal motion space of an agent of `role` at `self` playing against `opponent`: for a
/// pursuer, the cone of half-angle asin(v_E / v_P) about the line to the evader (eq. 6); for an evader,
/// the half-space alpha1 >= pi/2 away from the pursuer. nullopt when the two stand on the same point.
std::optional<Cone> motion_space(Role role, const Vec3& self, const Vec3& opponent, double self_speed,
                                 double opponent_speed);

/// Brings the unit direction `d` into `cone` when it lies outside: the nearest direction in the cone within
/// the climb limit (project_within_band). Near the direction opposite the cone's axis the side is taken
/// from `current` (the heading's direction) within `commit_angle`, so the choice does not flip each step.
/// Returns whether d changed.
bool keep_within(const Cone& cone, Vec3& d, double polar_margin, const Vec3& current, double commit_angle);

/// The angle (rad) within which the guard commits to the side the agent already leans to.
inline constexpr double kGuardCommitAngle = 0.35;  // 20 degrees

/// The headings the obstacle guard allows at `position` given the map's nearest obstacle (`nearest`, from the
/// distance field, arena faces excluded): everything but a cone about the direction to the obstacle, which
/// widens from nothing at warn_distance to a half-space at stop_distance. nullopt when the guard is off, no
/// obstacle is within warn_distance, or the agent stands on the obstacle point.
std::optional<Cone> guard_cone(const ObstacleGuard& guard, const Vec3& position, const ObstacleSense& nearest);

/// With guard.faces, what the guard keeps clear of at the arena's boundary: the boundary with its edges and
/// corners rounded by warn_distance. Near one face, the face's nearest point and distance; in a corner, the
/// nearest point of the rounding (nearer than either face), so the guard turns the agent out along the
/// diagonal. Not found beyond warn_distance from every face. `bounds` is the arena shrunk by `radius`.
ObstacleSense face_obstacle(const ObstacleGuard& guard, double radius, const Vec3& position, const Box& bounds);

/// The headings allowed by two guard cones, as one cone: the widest cone about the bisector of their axes
/// that lies inside both. When none does (the two exclude each other's every heading, or the axes are
/// opposite), `obstacle` alone: a collision ends a game, a face only stops the motion into it. `face` is a
/// face's cone or, against a face the agent touches, the half-space leaving it (guard_along_faces).
Cone allowed_by_both(const Cone& face, const Cone& obstacle);

/// Against a face of the arena the clamp removes the motion into the face, and what remains may still
/// approach the obstacle. `d` lies in `allowed` already (keep_within). If its part along the faces the agent
/// touches (`box` is the arena shrunk by its radius) is not allowed, d becomes the first allowed direction on
/// the arc, within those faces, towards the obstacle-free side (the face-plane part of the allowed cone's
/// axis). When that arc has no allowed direction within the climb limit (`polar_margin`), as when the
/// obstacle stands straight ahead along the face, d leaves the face instead: the direction nearest to d, within
/// the limit, in the widest cone about the bisector of the faces' inward normal and the allowed cone's axis
/// (allowed_by_both), the side taken from `current` like keep_within. Returns whether d changed.
bool guard_along_faces(const Cone& allowed, Vec3& d, const Vec3& position, const Box& box, double polar_margin,
                       const Heading& current);

/// Where the guard looks for a second obstacle: the map's obstacle nearest to a point, sensed as the agent's
/// nearest one is (AgentView::field).
class ObstacleProbe {
 public:
  /// The obstacle nearest to p when one lies within `reach` (m) of it; otherwise an answer farther than `reach`
  /// or none (a probe may stop looking there: the guard cannot use what lies beyond).
  virtual ObstacleSense nearest(const Vec3& p, double reach) const = 0;

 protected:
  ~ObstacleProbe() = default;
};

/// Brings d, inside `first` already, into `second` too: the direction of `second` nearest to d within the
/// climb limit if it lies in `first`, else the nearest direction on both cones' surfaces within the limit.
/// When none exists the two exclude each other and d stays (`first` has the last word). The side to turn to is
/// taken from `current` like keep_within. Returns whether d changed.
bool keep_within_both(const Cone& first, const Cone& second, Vec3& d, double polar_margin, const Heading& current);

/// Everything one agent's constrained heading depends on, at the start of a step. It refers to the caller's
/// data (built once per agent and step in the hot loop, so nothing is copied).
struct ConstraintInputs {
  const AgentConfig& config;
  Role role;
  double dt;                    ///< s
  const KinematicState& self;   ///< position and heading now
  const Vec3& opponent;         ///< the opponent's position now (for the motion space)
  double opponent_speed;        ///< m/s
  const ObstacleSense& field;   ///< the map's nearest obstacle (arena faces excluded)
  const Box& bounds;            ///< the arena shrunk by the agent's radius (where its centre may go)
  const ObstacleProbe* probe;   ///< for guard.look_ahead; null: the nearest obstacle only
  /// The map's static obstacles within hold_range of the agent, measured exactly (at most kMaxHeldPoints;
  /// CollisionWorld::obstacles_near), for the last resort of the guard: no step ends nearer to one than the
  /// agent's radius plus kHoldMargin.
  std::span<const world::NearPoint> near = {};
};

/// m added to the agent's radius: how near the guard's last resort lets a step end to an obstacle's surface.
inline constexpr double kHoldMargin = 0.02;
/// The most obstacle points ConstraintInputs::near may hold: the nearest ones count (a valley mesh gives up to
/// 7 triangles within hold_range, a forest 1 trunk).
inline constexpr int kMaxHeldPoints = 12;

/// m from the agent's centre within which an obstacle's surface can end a step too near (radius + kHoldMargin +
/// one step): the caller's `near` must hold every static obstacle point this near.
double hold_range(const AgentConfig& config, double dt);

/// The heading the agent takes for the command u: bounded steering, then the motion space (when enabled),
/// then the guard (when enabled): the map's nearest obstacle and, with guard.faces, the arena's faces too
/// (allowed_by_both when both are near), then a second obstacle ahead (guard.look_ahead, keep_within_both).
/// When a constraint moved the direction, the agent turns towards the constrained direction within the same
/// steering bound. With `moving`, also stores the step's motion per unit speed there: direction(heading),
/// computed once for the constraints and the move (the same bits as calling direction again), except that
/// within stop_distance of the map's nearest obstacle its part towards that obstacle is removed (the turn
/// bound can leave the heading still approaching; the agent slides past), and that, as a last resort, no step
/// ends nearer than radius + kHoldMargin to an obstacle of `near` (the nearest such motion, inside the arena).
Heading constrained_heading(const ConstraintInputs& in, const Steering& u, Vec3* moving = nullptr);

}  // namespace peg3d::game
