#include "game/episode.hpp"

#include <random>
#include <stdexcept>

#include <fmt/format.h>

#include "core/random.hpp"
#include "geometry/motion_cone.hpp"
#include "game/reward.hpp"

namespace peg3d::game {

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::kCapture: return "capture";
    case Outcome::kTimeout: return "timeout";
    case Outcome::kPursuerCollision: return "pursuer-collision";
    case Outcome::kEvaderCollision: return "evader-collision";
  }
  return "?";
}

Game::Game(std::shared_ptr<const world::Arena> arena, const GameConfig& config)
    : arena_(std::move(arena)), config_(config), collisions_(arena_) {
  config_.validate();
  pursuer_body_ = collisions_.add_agent(config_.pursuer.radius);
  evader_body_ = collisions_.add_agent(config_.evader.radius);
}

EpisodeState Game::start(const world::Scenario& scenario, std::uint64_t seed) {
  EpisodeState s;
  s.pursuer.position = arena_->bounds().shrunk(config_.pursuer.radius).clamp(scenario.pursuer.position);
  s.evader.position = arena_->bounds().shrunk(config_.evader.radius).clamp(scenario.evader.position);
  const Vec3 pe = s.evader.position - s.pursuer.position;
  const auto level = [](const Vec3& d) { return Heading{d.x() == 0.0 && d.y() == 0.0 ? 0.0 : std::atan2(d.y(), d.x()), kPi / 2}; };
  Rng rng(seed);
  auto initial = [&](Role r) -> Heading {
    switch (config_.initial_heading) {
      case InitialHeading::kChase: return level(pe);  // the pursuer faces the evader, the evader faces away
      case InitialHeading::kFacing: return level(r == Role::kPursuer ? pe : Vec3(-pe));
      case InitialHeading::kPlusX: return {0.0, kPi / 2};
      case InitialHeading::kRandom: {
        std::normal_distribution<double> n;
        Vec3 d(n(rng), n(rng), n(rng));
        return heading_of(d.squaredNorm() > 0.0 ? d : Vec3::UnitX());
      }
    }
    return {};
  };
  s.pursuer.heading = scenario.pursuer.heading.value_or(initial(Role::kPursuer));
  s.evader.heading = scenario.evader.heading.value_or(initial(Role::kEvader));

  collisions_.place_agent(pursuer_body_, s.pursuer.position);
  collisions_.place_agent(evader_body_, s.evader.position);
  for (const auto& [body, role] : {std::pair{pursuer_body_, Role::kPursuer}, std::pair{evader_body_, Role::kEvader}}) {
    if (const auto c = collisions_.overlap(body)) {
      throw std::runtime_error(fmt::format("scenario '{}': the {} starts overlapping {} {} (penetration {:.3f} m)",
                                           scenario.name, to_string(role), world::to_string(c->kind), c->obstacle_id,
                                           c->penetration));
    }
  }
  return s;
}

AgentView Game::view(Role role, const EpisodeState& s) const {
  const bool p = role == Role::kPursuer;
  const AgentConfig& self = config_.agent(role);
  AgentView v;
  v.role = role;
  v.self = p ? s.pursuer : s.evader;
  v.other = p ? s.evader : s.pursuer;
  v.self_speed = self.speed;
  v.other_speed = config_.agent(p ? Role::kEvader : Role::kPursuer).speed;
  v.dt = config_.dt;
  v.arena = arena_->bounds();
  // The map's shapes only: whether the arena's faces count is the agent's observation setting, not the map's.
  const world::NearestObstacle n = arena_->nearest_shape(v.self.position);
  v.field = {n.distance, n.point, n.found};
  v.percept = perceive(role, self, v.self, v.other, v.field, v.arena, arena_->max_distance());
  return v;
}

namespace {
constexpr double kGuardCommitAngle = 0.35;  // rad, 20 degrees
}  // namespace

Heading Game::next_heading(Role role, const EpisodeState& s, const AgentView& v, const Steering& u) const {
  const AgentConfig& c = config_.agent(role);
  const KinematicState& self = role == Role::kPursuer ? s.pursuer : s.evader;
  const double bound = c.steering.step_bound(config_.dt);
  const double margin = c.steering.polar_margin;
  const Heading requested = steer(self.heading, u, bound, margin);
  Vec3 d = direction(requested);
  bool changed = false;
  const auto constrain = [&](const Cone& cone, double commit_angle) {
    if (cone.contains(d)) return;
    d = project_within_band(cone, d, margin, direction(self.heading), commit_angle);
    changed = true;
  };
  const Vec3 pe = s.evader.position - s.pursuer.position;
  if (c.motion_space && pe.squaredNorm() > 0.0) {
    // Paper section 3.1: the pursuer keeps alpha2 <= asin(vE/vP) about P->E, the evader alpha1 >= pi/2.
    constrain(role == Role::kPursuer ? pursuer_motion_cone(s.pursuer.position, s.evader.position,
                                                           config_.pursuer.speed, config_.evader.speed)
                                     : evader_motion_cone(s.pursuer.position, s.evader.position),
              0.0);
  }
  // The guard comes last: staying clear of obstacles outranks the motion space.
  const Vec3 away = self.position - v.field.point;
  if (c.guard.enabled && v.field.found && v.field.distance < c.guard.warn_distance && away.squaredNorm() > 0.0) {
    const double excluded = 0.5 * kPi *
                            std::min(1.0, (c.guard.warn_distance - v.field.distance) /
                                              (c.guard.warn_distance - c.guard.stop_distance));
    const Cone allowed{away.normalized(), kPi - excluded};
    // Heading (almost) straight at the obstacle, the side to pass it on is the side the agent already
    // leans to; deciding it from the request would flip sides every step.
    constrain(allowed, kGuardCommitAngle);
    // Against an arena face the clamp removes the motion into the face, and what remains may still approach
    // the obstacle. Then the guard holds for the motion along the face: turn it, within the face, towards
    // the obstacle-free side (the face-plane part of `allowed`'s axis, always allowed as the cone is at
    // least a half-space).
    const Box box = arena_->bounds().shrunk(c.radius);
    Vec3 along = d, axis_along = allowed.axis;
    for (int a = 0; a < 3; ++a) {
      const bool at_lo = self.position[a] <= box.lo[a] + 1e-9, at_hi = self.position[a] >= box.hi[a] - 1e-9;
      if ((at_lo && along[a] < 0.0) || (at_hi && along[a] > 0.0)) along[a] = 0.0;
      if (at_lo || at_hi) axis_along[a] = 0.0;
    }
    if (along.squaredNorm() > 1e-12 && axis_along.squaredNorm() > 1e-12 && !allowed.contains(along.normalized())) {
      d = first_inside_on_arc(allowed, along.normalized(), axis_along.normalized());
      changed = true;
    }
  }
  if (!changed) return requested;
  // Turn towards the constrained direction within the same steering bound.
  const AngleErrors e = angle_errors(self.heading, d);
  return steer(self.heading, {e.azimuth, e.elevation}, bound, margin);
}

EpisodeResult Game::play(const world::Scenario& scenario, Policy& pursuer, Policy& evader, bool learning,
                         std::uint64_t seed, std::vector<StepRecord>* trace) {
  EpisodeState s = start(scenario, seed);
  EpisodeResult result;
  AgentView vp = view(Role::kPursuer, s), ve = view(Role::kEvader, s);
  pursuer.begin_episode(vp, learning);
  evader.begin_episode(ve, learning);
  if (trace) trace->push_back({0.0, s.pursuer, s.evader, vp.percept, ve.percept, {}, {}, 0.0, 0.0});

  const int max_steps = config_.max_steps();
  const double max_closing = (config_.pursuer.speed + config_.evader.speed) * config_.dt;
  const Box p_box = arena_->bounds().shrunk(config_.pursuer.radius);
  const Box e_box = arena_->bounds().shrunk(config_.evader.radius);
  double distance = vp.percept.target_distance;

  while (true) {
    const Steering up = pursuer.act(vp);
    const Steering ue = evader.act(ve);

    EpisodeState n = s;
    n.pursuer.heading = next_heading(Role::kPursuer, s, vp, up);
    n.evader.heading = next_heading(Role::kEvader, s, ve, ue);
    n.pursuer.position = p_box.clamp(s.pursuer.position + config_.pursuer.speed * config_.dt * direction(n.pursuer.heading));
    n.evader.position = e_box.clamp(s.evader.position + config_.evader.speed * config_.dt * direction(n.evader.heading));

    bool collided[2] = {false, false};
    for (const Role r : {Role::kPursuer, Role::kEvader}) {
      const bool is_p = r == Role::kPursuer;
      KinematicState& k = is_p ? n.pursuer : n.evader;
      const int body = is_p ? pursuer_body_ : evader_body_;
      if (const auto c = collisions_.move_agent(body, k.position)) {
        k.position = collisions_.agent_position(body);  // stopped at the time of impact
        collided[is_p ? 0 : 1] = true;
        ++result.collisions;
        if (!result.first_collision) {
          result.first_collision = CollisionEvent{s.time + c->fraction * config_.dt, r, c->kind, c->obstacle_id,
                                                  c->point, c->fraction, c->penetration};
        }
      }
    }
    result.pursuer_path += (n.pursuer.position - s.pursuer.position).norm();
    result.evader_path += (n.evader.position - s.evader.position).norm();
    n.step = s.step + 1;
    n.time = n.step * config_.dt;

    const AgentView np = view(Role::kPursuer, n), ne = view(Role::kEvader, n);
    const double next_distance = np.percept.target_distance;
    const bool captured = next_distance <= config_.capture_distance;
    const bool crash = config_.collision == CollisionMode::kTerminate && (collided[0] || collided[1]);
    const bool timeout = n.step >= max_steps;

    const RewardTerms rp = reward(Role::kPursuer, config_.pursuer.reward,
                                  {distance, next_distance, vp.percept.obstacle.distance, np.percept.obstacle.distance,
                                   captured, collided[0]},
                                  max_closing);
    const RewardTerms re = reward(Role::kEvader, config_.evader.reward,
                                  {distance, next_distance, ve.percept.obstacle.distance, ne.percept.obstacle.distance,
                                   captured, collided[1]},
                                  max_closing);
    result.pursuer_return += rp.total;
    result.evader_return += re.total;
    result.pursuer_pinned_steps += np.percept.pinned;
    result.evader_pinned_steps += ne.percept.pinned;

    // The time limit truncates the episode; it is not a terminal state of the game, so learners bootstrap.
    const bool terminal = captured || crash;
    if (learning) {
      pursuer.learn(rp.total, np, terminal);
      evader.learn(re.total, ne, terminal);
    }
    if (trace) trace->push_back({n.time, n.pursuer, n.evader, np.percept, ne.percept, up, ue, rp.total, re.total});

    s = n;
    vp = np;
    ve = ne;
    distance = next_distance;
    if (captured || crash || timeout) {
      result.outcome = captured ? Outcome::kCapture
                       : crash  ? (collided[0] ? Outcome::kPursuerCollision : Outcome::kEvaderCollision)
                                : Outcome::kTimeout;
      break;
    }
  }
  result.steps = s.step;
  result.duration = s.time;
  result.final_distance = distance;
  return result;
}

}  // namespace peg3d::game
