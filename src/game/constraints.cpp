#include "game/constraints.hpp"

#include <algorithm>
#include <array>
#include <cassert>

#include "geometry/half_spaces.hpp"

namespace peg3d::game {

Heading bounded_steer(const Heading& h, const Steering& u, const SteeringConfig& steering, double dt) {
  return steer(h, u, steering.step_bound(dt), steering.polar_margin);
}

std::optional<Cone> motion_space(Role role, const Vec3& self, const Vec3& opponent, double self_speed,
                                 double opponent_speed) {
  const Vec3& pursuer = role == Role::kPursuer ? self : opponent;
  const Vec3& evader = role == Role::kPursuer ? opponent : self;
  if ((evader - pursuer).squaredNorm() == 0.0) return std::nullopt;
  if (role == Role::kPursuer) return pursuer_motion_cone(pursuer, evader, self_speed, opponent_speed);
  return evader_motion_cone(pursuer, evader);
}

bool keep_within(const Cone& cone, Vec3& d, double polar_margin, const Vec3& current, double commit_angle) {
  if (cone.contains(d)) return false;
  d = project_within_band(cone, d, polar_margin, current, commit_angle);
  return true;
}

namespace {
// keep_within with the heading's direction computed only when a projection needs it (a sincos pair saved
// on every unconstrained step).
bool keep_within_heading(const Cone& cone, Vec3& d, double polar_margin, const Heading& current, double commit_angle) {
  if (cone.contains(d)) return false;
  d = project_within_band(cone, d, polar_margin, direction(current), commit_angle);
  return true;
}
}  // namespace

std::optional<Cone> guard_cone(const ObstacleGuard& guard, const Vec3& position, const ObstacleSense& nearest) {
  const Vec3 away = position - nearest.point;
  if (!guard.enabled || !nearest.found || !(nearest.distance < guard.warn_distance) || away.squaredNorm() == 0.0) {
    return std::nullopt;
  }
  const double excluded =
      0.5 * kPi *
      std::min(1.0, (guard.warn_distance - nearest.distance) / (guard.warn_distance - guard.stop_distance));
  return Cone{away.normalized(), kPi - excluded};
}

ObstacleSense face_obstacle(const ObstacleGuard& guard, double radius, const Vec3& position, const Box& bounds) {
  // The faces as the guard sees them: the arena (bounds grown back by the radius) with its edges and corners
  // rounded by warn_distance. Near one face that is the face itself; in a corner the nearest point lies on the
  // rounding, so the agent is turned out of the corner along the diagonal instead of into the other face.
  const double w = guard.warn_distance;
  const Box arena = bounds.shrunk(-radius);
  const Vec3 lo = arena.lo.array() + w, hi = arena.hi.array() - w;
  const Vec3 centre = 0.5 * (arena.lo + arena.hi);
  // The inner box, collapsed to the arena's middle along an axis shorter than 2 w.
  const Vec3 inner_lo = lo.cwiseMin(centre), inner_hi = hi.cwiseMax(centre);
  const Vec3 out = position - position.cwiseMax(inner_lo).cwiseMin(inner_hi);
  const double r = out.norm();
  ObstacleSense face;
  if (!(r > 0.0)) return face;  // farther than warn_distance from every face: not found
  face.distance = std::max(w - r, 0.0);
  face.point = position + out * (face.distance / r);
  face.found = true;
  return face;
}

Cone allowed_by_both(const Cone& face, const Cone& obstacle) {
  // The cone about the bisector of the two axes that fits inside both: its half-angle is each cone's minus
  // the bisector's angle from that cone's axis.
  const Vec3 sum = face.axis + obstacle.axis;
  if (sum.squaredNorm() < 1e-12) return obstacle;
  const Vec3 bisector = sum.normalized();
  const double half = std::min(face.half_angle - angle_between(bisector, face.axis),
                               obstacle.half_angle - angle_between(bisector, obstacle.axis));
  return half > 1e-6 ? Cone{bisector, half} : obstacle;
}

bool guard_along_faces(const Cone& allowed, Vec3& d, const Vec3& position, const Box& box, double polar_margin,
                       const Heading& current) {
  Vec3 along = d, axis_along = allowed.axis, inward = Vec3::Zero();
  for (int a = 0; a < 3; ++a) {
    const bool at_lo = position[a] <= box.lo[a] + 1e-9, at_hi = position[a] >= box.hi[a] - 1e-9;
    if ((at_lo && along[a] < 0.0) || (at_hi && along[a] > 0.0)) along[a] = 0.0;
    if (at_lo || at_hi) axis_along[a] = 0.0;
    inward[a] = at_lo ? 1.0 : at_hi ? -1.0 : 0.0;
  }
  if (along.squaredNorm() <= 1e-12 || axis_along.squaredNorm() <= 1e-12 || allowed.contains(along.normalized())) {
    return false;
  }
  const Vec3 slide_from = along.normalized(), slide_to = axis_along.normalized();
  if (angle_between(slide_from, slide_to) < kPi - 1e-6) {
    const Vec3 slide = first_inside_on_arc(allowed, slide_from, slide_to);
    if (within_climb_limit(slide, polar_margin)) {
      d = slide;
      return true;
    }
  }
  // No allowed slide within the climb limit (the obstacle lies straight ahead along the face, or the only
  // allowed slides are steeper than the limit): leave the face instead, in the widest cone about the bisector
  // of the faces' inward normal and the guard's axis, within the climb limit. Turning towards a slide outside
  // the limit would keep the heading's azimuth and run into the obstacle.
  d = project_within_band(allowed_by_both(Cone{inward.normalized(), kPi / 2}, allowed), d, polar_margin,
                          direction(current), kGuardCommitAngle);
  return true;
}

bool keep_within_both(const Cone& first, const Cone& second, Vec3& d, double polar_margin, const Heading& current) {
  if (second.contains(d)) return false;
  // The heading's direction only when a projection needs it, as keep_within_heading.
  const Vec3 p = project_within_band(second, d, polar_margin, direction(current), kGuardCommitAngle);
  if (first.contains(p, 1e-9) && second.contains(p, 1e-9) && within_climb_limit(p, polar_margin)) {
    d = p;
    return true;
  }
  // Both cones bind: the answer lies where their surfaces cross.
  std::optional<Vec3> best;
  for (const Vec3& u : boundary_crossings(first, second)) {
    if (within_climb_limit(u, polar_margin) && (!best || u.dot(d) > best->dot(d))) best = u;
  }
  if (!best) return false;
  d = *best;
  return true;
}

namespace {
// The guard's cone of the second obstacle: the one nearest to the point look_ahead ahead along d, when it is
// another than the nearest one and nearer than stop_distance (then a half-space). Probed only near an obstacle.
std::optional<Cone> second_obstacle_cone(const ConstraintInputs& in, const Vec3& d) {
  const ObstacleGuard& g = in.config.guard;
  if (in.probe == nullptr || !(g.look_ahead > 0.0) || !in.field.found || !(in.field.distance < g.warn_distance)) {
    return std::nullopt;
  }
  const Vec3& p = in.self.position;
  // A point farther than look_ahead + stop_distance from the probed point lies farther than stop_distance from
  // the agent (d is a unit vector), so it gives no cone: the probe need not look beyond (the margin covers
  // the rounding of both distances).
  const ObstacleSense ahead = in.probe->nearest(p + g.look_ahead * d, g.look_ahead + g.stop_distance + 1e-9);
  if (!ahead.found || (ahead.point - in.field.point).squaredNorm() < 1e-18) return std::nullopt;
  const double distance = (ahead.point - p).norm();
  if (!(distance < g.stop_distance)) return std::nullopt;
  return guard_cone(g, p, ObstacleSense{distance, ahead.point, true});
}

// The guard's promise, no approach to an obstacle within stop_distance, kept for the motion. The turn bound
// can leave the heading short of the guarded direction, still approaching the nearest obstacle (two trunks,
// one on each side, the nearest alternating between them step by step). Then the motion loses its part
// towards the nearest obstacle, as the clamp removes the motion into a face: for that step the agent slides
// past, slower.
//
// The field's nearest is one voxel of one obstacle: between two trunks it may name the other one, and the
// step then closes on this one. The last resort holds against every obstacle point in `near`, exact: the
// step s m keeps each at least the clearance c = radius + kHoldMargin away, to first order,
//     s m . n <= d - c          (n towards the point, d its distance),
// which holds exactly for a convex piece (its distance is convex along the step): spheres, cylinders and each
// triangle of a mesh. It only binds when a step would end within c; then the motion is the nearest one that
// keeps every point's clearance, the stop_distance rule above and the arena (the clamp would move it after).
void hold_clear_of_obstacle(const ConstraintInputs& in, Vec3& m) {
  const ObstacleGuard& g = in.config.guard;
  if (!g.enabled) return;
  const Vec3& p = in.self.position;
  const Vec3 requested = m;
  std::optional<HalfSpace> nearest;
  if (in.field.found && in.field.distance < g.stop_distance) {
    const Vec3 to = in.field.point - p;
    if (to.squaredNorm() > 0.0) {
      nearest = HalfSpace{to.normalized(), 0.0};
      const double approach = m.dot(nearest->normal);
      if (approach > 0.0) m -= approach * nearest->normal;
    }
  }
  const double step = in.config.speed * in.dt;
  if (in.near.empty() || !(step > 0.0)) return;
  assert(in.near.size() <= std::size_t(kMaxHeldPoints));
  const double clearance = in.config.radius + kHoldMargin;
  std::array<HalfSpace, kMaxHeldPoints + 4> h;
  std::size_t k = 0;
  for (const world::NearPoint& o : in.near) {
    const Vec3 to = o.point - p;
    const double d = to.norm();
    if (d > 0.0) h[k++] = HalfSpace{to / d, std::max(d - clearance, 0.0) / step};
  }
  // Checked where the clamp puts the step: it removes the motion into a face, and what remains may close on a
  // point that the motion before it kept clear of.
  const Vec3 moved = (in.bounds.clamp(p + step * m) - p) / step;
  if (std::all_of(h.begin(), h.begin() + k, [&](const HalfSpace& s) { return moved.dot(s.normal) <= s.offset; })) {
    return;
  }
  if (nearest) h[k++] = *nearest;
  for (int a = 0; a < 3; ++a) {
    // The arena as half-spaces of the motion, where one step could reach a face.
    const double below = (p[a] - in.bounds.lo[a]) / step, above = (in.bounds.hi[a] - p[a]) / step;
    if (below < 1.0) h[k++] = HalfSpace{-Vec3::Unit(a), std::max(below, 0.0)};
    else if (above < 1.0) h[k++] = HalfSpace{Vec3::Unit(a), std::max(above, 0.0)};
  }
  m = nearest_within(requested, std::span<const HalfSpace>(h.data(), k));
}

}  // namespace

double hold_range(const AgentConfig& config, double dt) {
  return config.radius + kHoldMargin + config.speed * dt;
}

Heading constrained_heading(const ConstraintInputs& in, const Steering& u, Vec3* moving) {
  const AgentConfig& c = in.config;
  const double margin = c.steering.polar_margin;
  const Heading requested = bounded_steer(in.self.heading, u, c.steering, in.dt);
  Vec3 d = direction(requested);
  bool changed = false;
  if (c.motion_space) {
    if (const auto cone = motion_space(in.role, in.self.position, in.opponent, c.speed, in.opponent_speed)) {
      changed |= keep_within_heading(*cone, d, margin, in.self.heading, 0.0);
    }
  }
  // The guard comes last: staying clear of obstacles outranks the motion space.
  std::optional<Cone> allowed = guard_cone(c.guard, in.self.position, in.field);
  if (c.guard.faces) {
    if (const auto face = guard_cone(c.guard, in.self.position, face_obstacle(c.guard, c.radius, in.self.position, in.bounds))) {
      allowed = allowed ? allowed_by_both(*face, *allowed) : face;
    }
  }
  if (allowed) {
    // Heading (almost) straight at the obstacle, the side to pass it on is the side the agent already leans
    // to; deciding it from the request would flip sides every step.
    changed |= keep_within_heading(*allowed, d, margin, in.self.heading, kGuardCommitAngle);
    if (const auto second = second_obstacle_cone(in, d)) {
      changed |= keep_within_both(*allowed, *second, d, margin, in.self.heading);
    }
    changed |= guard_along_faces(*allowed, d, in.self.position, in.bounds, margin, in.self.heading);
  }
  Heading h = requested;
  if (changed) {
    // Turn towards the constrained direction within the same steering bound.
    const AngleErrors e = angle_errors(in.self.heading, d);
    h = bounded_steer(in.self.heading, {e.azimuth, e.elevation}, c.steering, in.dt);
  }
  if (moving) {
    *moving = changed ? direction(h) : d;  // unchanged, d is direction(requested)
    hold_clear_of_obstacle(in, *moving);
  }
  return h;
}

}  // namespace peg3d::game
