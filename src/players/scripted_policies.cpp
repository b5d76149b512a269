#include "players/scripted_policies.hpp"

#include <array>
#include <cmath>
#include <optional>

#include "geometry/apollonius.hpp"
#include "geometry/plane_section.hpp"

namespace peg3d::players {

Steering steer_toward(const game::AgentView& view, const Vec3& direction) {
  if (direction.squaredNorm() == 0.0) return {};
  const AngleErrors e = angle_errors(view.self.heading, direction);
  return {e.azimuth, e.elevation};
}

namespace {

Vec3 velocity(const KinematicState& s, double speed) { return speed * peg3d::direction(s.heading); }

// Where the view's evader, on its straight course at its speed, meets this agent heading straight for it, held in
// the arena (geometry/apollonius.hpp); nothing for an evader at rest or one it never meets.
std::optional<Vec3> interception_goal(const game::AgentView& view) {
  if (!(view.other_speed > 0.0)) return std::nullopt;
  const auto x = interception_point(view.self.position, view.other.position, peg3d::direction(view.other.heading),
                                    view.other_speed / view.self_speed);
  if (!x) return std::nullopt;
  return view.arena.clamp(*x);
}

// Fixed, evenly spread unit directions (a Fibonacci sphere) to search the Apollonius sphere with.
constexpr int kSearchDirections = 256;
const std::array<Vec3, kSearchDirections>& search_directions() {
  static const std::array<Vec3, kSearchDirections> dirs = [] {
    std::array<Vec3, kSearchDirections> d;
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kSearchDirections; ++i) {
      const double z = 1.0 - 2.0 * (i + 0.5) / kSearchDirections;
      const double r = std::sqrt(1.0 - z * z);
      d[i] = Vec3(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return d;
  }();
  return dirs;
}

}  // namespace

Vec3 repulsion(const game::AgentView& view) {
  auto push = [](double d) {
    const double k = (kAvoidDistance - d) / kAvoidDistance;
    return d < kAvoidDistance ? 3.0 * k * k : 0.0;
  };
  Vec3 r = Vec3::Zero();
  const Vec3& p = view.self.position;
  for (int axis = 0; axis < 3; ++axis) {
    r[axis] += push(p[axis] - view.arena.lo[axis]);
    r[axis] -= push(view.arena.hi[axis] - p[axis]);
  }
  const game::ObstacleSense& o = view.percept.obstacle;
  const Vec3 away = p - o.point;
  if (o.found && away.squaredNorm() > 0.0) r += push(o.distance) * away.normalized();
  return r;
}

Steering PurePursuit::act(const game::AgentView& view) { return steer_toward(view, view.other.position - view.self.position); }

Steering ProportionalNavigation::act(const game::AgentView& view) {
  const Vec3 r = view.other.position - view.self.position;
  const Vec3 dir = peg3d::direction(view.self.heading);
  if (r.squaredNorm() == 0.0 || dir.dot(r) <= 0.0) return steer_toward(view, r);
  const Vec3 v_rel = velocity(view.other, view.other_speed) - velocity(view.self, view.self_speed);
  const Vec3 omega = r.cross(v_rel) / r.squaredNorm();  // line-of-sight rotation rate, rad/s
  const Vec3 turned = dir + gain_ * omega.cross(dir) * view.dt;
  return steer_toward(view, turned);
}

Steering ApolloniusInterceptor::act(const game::AgentView& view) {
  const Vec3& p = view.self.position;
  if (const auto x = interception_goal(view)) return steer_toward(view, *x - p);
  return steer_toward(view, view.other.position - p);
}

void VoronoiPursuer::begin_episode(const game::AgentView& view, bool learning) {
  (void)learning;
  if (way_ != VoronoiWay::kStraight && view.probe != nullptr) roadmap_.build(view.arena, *view.probe);  // the solids may have moved
}

std::optional<Vec3> VoronoiPursuer::face_goal(const game::AgentView& view, const Vec3& e) {
  const Vec3& p = view.self.position;
  if (geodesic(view)) {
    sources_.assign(1, e);
    for (const KinematicState& q : view.team) sources_.push_back(q.position);
    roadmap_.partition(sources_);
    std::optional<Vec3> goal = roadmap_.border_point(view.rank + 1);
    if (!goal && view.self_speed > 0.0 && view.other_speed > view.self_speed) {
      // No face with its Voronoi cell: the border of what the faster evader reaches first (its Apollonius cell)
      // instead, where it would slip past, rather than trailing the team along the shortest way to it.
      roadmap_.partition(sources_, view.other_speed / view.self_speed);
      goal = roadmap_.border_point(view.rank + 1);
    }
    if (goal) goal->z() = e.z();  // at the evader's height
    return goal;
  }
  // The face: the bisector plane of e and p, within the arena, where no other pursuer q is nearer than e:
  // x . (q - e) <= (|q|^2 - |e|^2) / 2.
  cuts_.clear();
  for (std::size_t k = 0; k < view.team.size(); ++k) {
    const Vec3& q = view.team[k].position;
    const double apart = (q - e).norm();
    if (int(k) == view.rank || apart == 0.0) continue;
    cuts_.push_back({(q - e) / apart, 0.5 * (q.squaredNorm() - e.squaredNorm()) / apart});
  }
  const Vec3 normal = (p - e).normalized();
  plane_section(0.5 * (p + e), normal, view.arena, cuts_, face_, scratch_);
  if (face_.empty()) return std::nullopt;
  return polygon_centroid(face_, normal);
}

Steering VoronoiPursuer::act(const game::AgentView& view) {
  // The evader where it will be in kVoronoiLead at its speed and heading, held in the arena.
  const Vec3 e =
      view.arena.clamp(view.other.position + kVoronoiLead * view.other_speed * peg3d::direction(view.other.heading));
  const Vec3& p = view.self.position;
  bool chase = view.team.size() < 2 || (e - p).norm() < (geodesic(view) ? kVoronoiGeodesicChase : kVoronoiChase) ||
               view.other_age > kVoronoiSightAge;
  Vec3 goal = view.other.position;
  if (!chase) {
    const std::optional<Vec3> face = face_goal(view, e);
    chase = !face;
    if (face) goal = *face;
  }
  if (chase && chase_way_ == VoronoiChase::kInterception && view.other_age <= kVoronoiSightAge &&
      view.self_speed > 0.0) {
    // Where the courses meet (always for a slower evader, for a faster one only while it comes this way), cut it off.
    if (const auto x = interception_goal(view)) {
      goal = *x;
      chase = false;
    }
  }
  if (way_ != VoronoiWay::kStraight && view.probe != nullptr && roadmap_.cells() > 0 &&
      !passable(*view.probe, p, goal, kPassage)) {
    if (const auto way = roadmap_.waypoint(*view.probe, p, goal, kPassage)) return steer_toward(view, *way - p);
  }
  return chase ? chase_.act(view) : steer_toward(view, goal - p);
}

Steering FleeLineOfSight::act(const game::AgentView& view) {
  const Vec3 away = (view.self.position - view.other.position).normalized();
  return steer_toward(view, away + repulsion(view));
}

Steering FleeApollonius::act(const game::AgentView& view) {
  const Vec3& e = view.self.position;
  const Vec3& p = view.other.position;
  const double a = view.other_speed > 0.0 ? view.self_speed / view.other_speed : 2.0;
  if (a >= 1.0 - kUnitRatioTolerance || (e - p).squaredNorm() == 0.0) {
    return steer_toward(view, (e - p).normalized() + repulsion(view));  // no bounded dominance region: flee
  }
  const ApolloniusSurface surface(p, e, a);
  const Box inside = view.arena.shrunk(1.0);
  Vec3 goal = inside.clamp(surface.sphere().center);
  double best = (goal - p).squaredNorm();
  for (const Vec3& d : search_directions()) {
    const Vec3 x = surface.sphere().center + surface.sphere().radius * d;
    if (!inside.contains(x)) continue;
    if (const double dist = (x - p).squaredNorm(); dist > best) {
      best = dist;
      goal = x;
    }
  }
  const Vec3 to_goal = goal - e;
  const double n = to_goal.norm();
  return steer_toward(view, (n > 1e-9 ? Vec3(to_goal / n) : Vec3((e - p).normalized())) + repulsion(view));
}

Steering RandomWalk::act(const game::AgentView& view) {
  const double bound = steering_.step_bound(view.dt);
  return {bound * u_(rng_), bound * u_(rng_)};
}

}  // namespace peg3d::players
