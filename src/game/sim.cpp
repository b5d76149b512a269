#include "game/sim.hpp"

#include <cassert>
#include <cmath>
#include <limits>
#include <random>

#include <fmt/format.h>

#include "core/step_profile.hpp"
#include "core/validation.hpp"
#include "game/constraints.hpp"
#include "geometry/sphere_sweep.hpp"
#include "world/movers.hpp"

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

namespace {

// After an agent-agent contact both agents are set back this far along their paths (as CollisionWorld does
// for obstacles), so they end the step apart.
constexpr double kAgentBackoff = 1e-3;  // m

void check_counts(const world::Scenario& s) {
  const auto check = [&](std::size_t n, const char* role) {
    if (n < 1 || n > static_cast<std::size_t>(world::kMaxAgentsPerRole)) {
      throw InvalidParameter(fmt::format("scenario '{}' {}s", s.name, role), std::to_string(n),
                             fmt::format("must lie in [1, {}]", world::kMaxAgentsPerRole));
    }
  };
  check(s.pursuers.size(), "pursuer");
  check(s.evaders.size(), "evader");
}

bool pair_collides(AgentCollisions rule, Role a, Role b) {
  switch (rule) {
    case AgentCollisions::kNone: return false;
    case AgentCollisions::kOpponents: return a != b;
    case AgentCollisions::kTeammates: return a == b;
    case AgentCollisions::kAll: return true;
  }
  return false;
}

// Places the scenario's agents (bodies 0..n-1 of `world`, radii set) and throws StartError for the first
// agent, in index order, whose sphere overlaps an obstacle or, when agents collide, an earlier agent.
void check_overlaps(const Sim& sim, world::CollisionWorld& world, const world::Scenario& s,
                    const std::vector<Vec3>& positions) {
  const GameConfig& g = sim.config();
  const int n = s.agents(), p = static_cast<int>(s.pursuers.size());
  const std::filesystem::path& file = sim.arena().map().source;
  for (int i = 0; i < n; ++i) {
    const Role role = role_at(i, p);
    const world::AgentStart& a = s.start(i);
    const double radius = g.agent_at(i, p).radius;
    if (sim.arena().below_solid_terrain(positions[std::size_t(i)])) {
      throw StartError(file, a.line, a.field.empty() ? "scenario " + s.name : a.field,
                       fmt::format("scenario '{}': the {} starts under solid terrain", s.name, to_string(role)));
    }
    if (const auto c = world.overlap(i)) {
      throw StartError(file, a.line, a.field.empty() ? "scenario " + s.name : a.field,
                       fmt::format("scenario '{}': the {} (radius {} m) starts overlapping {} {} (penetration {:.3f} m)",
                                   s.name, to_string(role), radius, world::to_string(c->kind), c->obstacle_id,
                                   c->penetration));
    }
    if (const world::MoverTimeline* movers = sim.movers()) {
      for (int m = 0; m < movers->count(); ++m) {
        const double gap = signed_distance(movers->mover(m).shape, movers->pose(m, 0.0), positions[std::size_t(i)]) - radius;
        if (gap < 0.0) {
          throw StartError(file, a.line, a.field.empty() ? "scenario " + s.name : a.field,
                           fmt::format("scenario '{}': the {} (radius {} m) starts overlapping {} (penetration {:.3f} m)",
                                       s.name, to_string(role), radius,
                                       world::describe_mover(movers->mover(m), m), -gap));
        }
      }
    }
    for (int j = 0; j < i; ++j) {
      if (!pair_collides(g.team.agent_collisions, role, role_at(j, p))) continue;
      const double reach = radius + g.agent_at(j, p).radius;
      if ((positions[std::size_t(i)] - positions[std::size_t(j)]).norm() <= reach) {
        throw StartError(file, a.line, a.field.empty() ? "scenario " + s.name : a.field,
                         fmt::format("scenario '{}': the {} starts overlapping agent {} (agents collide: {})", s.name,
                                     to_string(role), j, config::enum_name(kAgentCollisionNames, g.team.agent_collisions)));
      }
    }
  }
}

// The start positions of a scenario's agents, kept radius inside the arena.
void start_positions(const Sim& sim, const world::Scenario& s, std::vector<Vec3>& out) {
  const int n = s.agents(), p = static_cast<int>(s.pursuers.size());
  out.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double radius = sim.config().agent_at(i, p).radius;
    out[std::size_t(i)] = sim.arena().bounds().shrunk(radius).clamp(s.start(i).position);
  }
}

Heading level(const Vec3& d) {
  return {d.x() == 0.0 && d.y() == 0.0 ? 0.0 : std::atan2(d.y(), d.x()), kPi / 2};
}

// The map's obstacle nearest to p at the state's time: its shapes only (whether the arena's faces count is the
// agent's observation setting, not the map's) and, on a map with movers, the nearer of them and the field.
ObstacleSense sense_obstacle(const Sim& sim, const SimState& st, const Vec3& p) {
  const world::NearestObstacle n = st.moving_field ? st.moving_field->nearest(p) : sim.arena().nearest_shape(p);
  if (const world::MoverTimeline* movers = sim.movers(); movers != nullptr && !st.moving_field) {
    // Moving obstacles where they are now, exactly.
    const world::MoverPoint m = movers->nearest(p, st.time, n.distance);
    if (m.mover >= 0) return {m.distance, m.point, true};
  }
  return {n.distance, n.point, n.found};
}

// The guard's look ahead senses as the agent does.
class StateProbe final : public ObstacleProbe {
 public:
  StateProbe(const Sim& sim, const SimState& st) : sim_(sim), st_(st) {}
  ObstacleSense nearest(const Vec3& p) const override { return sense_obstacle(sim_, st_, p); }

 private:
  const Sim& sim_;
  const SimState& st_;
};

// Rebuilds the agent's view from its position and its opponent's state.
void perceive_agent(const Sim& sim, SimState& st, int i) {
  AgentState& a = st.agents[std::size_t(i)];
  const AgentState& o = st.agents[std::size_t(a.opponent)];
  AgentView& v = a.view;
  v.role = a.role;
  v.index = i;
  v.opponent = a.opponent;
  v.self = a.kinematics;
  v.other = o.kinematics;
  v.self_speed = a.config->speed;
  v.other_speed = o.config->speed;
  v.dt = sim.config().dt;
  v.time = st.time;
  v.arena = sim.arena().bounds();
  v.field = sense_obstacle(sim, st, a.kinematics.position);
  v.percept = perceive(a.role, *a.config, a.kinematics, o.kinematics, v.field, sim.arena().bounds(),
                       sim.arena().max_distance());
}

OpponentChoice rule_of(const GameConfig& g, Role role) {
  return role == Role::kPursuer ? g.team.pursuer_target : g.team.evader_threat;
}

}  // namespace

int choose_opponent(const SimState& st, int i, OpponentChoice rule) {
  const AgentState& a = st.agents[std::size_t(i)];
  const int lo = a.role == Role::kPursuer ? st.pursuers : 0;
  const int hi = a.role == Role::kPursuer ? st.agent_count() : st.pursuers;
  if (hi - lo == 1) return st.agents[std::size_t(lo)].active ? lo : a.opponent;  // one against one
  if (rule == OpponentChoice::kAssigned && hi > lo) {
    const int k = lo + a.rank % (hi - lo);
    if (st.agents[std::size_t(k)].active) return k;
  }
  int best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int j = lo; j < hi; ++j) {
    const AgentState& o = st.agents[std::size_t(j)];
    if (!o.active) continue;
    const double d2 = (o.kinematics.position - a.kinematics.position).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = j;
  }
  return best >= 0 ? best : a.opponent;
}

Sim::Sim(std::shared_ptr<const world::Arena> arena, GameConfig config)
    : arena_(std::move(arena)), config_(std::make_shared<const GameConfig>(std::move(config))) {
  config_->validate();
  max_steps_ = config_->max_steps();
  const world::MapSpec& map = arena_->map();
  if (!map.movers.empty()) {
    const double substeps = config_->dt * map.physics.rate_hz;
    if (std::abs(substeps - std::round(substeps)) > 1e-9 * std::max(1.0, substeps) || std::round(substeps) < 1.0) {
      throw world::MapError(map.source, map.physics.line, "physics.rate_hz",
                            fmt::format("{} Hz does not divide the game step dt = {} s into whole substeps",
                                        map.physics.rate_hz, config_->dt));
    }
    movers_ = arena_->movers_until(config_->time_limit + config_->dt);
  }
  if (arena_->map().scenarios.empty()) return;
  world::CollisionWorld world(arena_);
  std::vector<Vec3> positions;
  for (const world::Scenario& s : arena_->map().scenarios) {
    check_counts(s);
    start_positions(*this, s, positions);
    while (world.agent_count() < s.agents()) world.add_agent(1.0);
    const int p = static_cast<int>(s.pursuers.size());
    for (int i = 0; i < s.agents(); ++i) {
      world.set_agent_radius(i, config_->agent_at(i, p).radius);
      world.place_agent(i, positions[std::size_t(i)]);
    }
    check_overlaps(*this, world, s, positions);
  }
}

void Sim::check_scenario(const world::Scenario& s) const {
  check_counts(s);
  world::CollisionWorld world(arena_);
  std::vector<Vec3> positions;
  start_positions(*this, s, positions);
  const int p = static_cast<int>(s.pursuers.size());
  for (int i = 0; i < s.agents(); ++i) {
    world.add_agent(config_->agent_at(i, p).radius);
    world.place_agent(i, positions[std::size_t(i)]);
  }
  check_overlaps(*this, world, s, positions);
}

SimState::SimState(const Sim& sim) : collider(sim.arena_ptr()) {}

void reset(const Sim& sim, SimState& st, const world::Scenario& scenario, std::uint64_t seed) {
  check_counts(scenario);
  const GameConfig& g = sim.config();
  const int n = scenario.agents(), p = static_cast<int>(scenario.pursuers.size());
  st.pursuers = p;
  st.agents.resize(static_cast<std::size_t>(n));
  st.scratch.next.resize(static_cast<std::size_t>(n));
  st.scratch.target_before.resize(static_cast<std::size_t>(n));
  st.scratch.obstacle_before.resize(static_cast<std::size_t>(n));
  st.scratch.positions.resize(static_cast<std::size_t>(n));
  st.events.agents.assign(static_cast<std::size_t>(n), AgentEvents{});
  st.events.collisions.clear();
  st.events.collisions.reserve(static_cast<std::size_t>(3 * n));
  st.events.captures.clear();
  st.events.captures.reserve(static_cast<std::size_t>(n));
  st.events.terminal = st.events.truncated = false;
  st.time = 0.0;
  st.step = 0;
  st.free_evaders = n - p;
  st.done = false;
  st.outcome = Outcome::kTimeout;
  st.first_collision.reset();
  st.collisions = 0;
  // A margin above d_s^2 so that rounding can never skip a pair whose distance is <= d_s.
  st.scratch.capture_reach2 = g.capture_distance * g.capture_distance * (1.0 + 1e-9) + 1e-12;
  while (st.collider.agent_count() < n) st.collider.add_agent(1.0);

  start_positions(sim, scenario, st.scratch.positions);
  for (int i = 0; i < n; ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    a = AgentState{};
    a.role = role_at(i, p);
    a.rank = rank_at(i, p);
    a.config = &g.agent(a.role, a.rank);
    a.bounds = sim.arena().bounds().shrunk(a.config->radius);
    a.body = i;
    a.kinematics.position = st.scratch.positions[std::size_t(i)];
    st.collider.set_agent_radius(i, a.config->radius);
  }
  for (int i = 0; i < n; ++i) st.agents[std::size_t(i)].opponent = choose_opponent(st, i, OpponentChoice::kNearest);

  // Headings: the scenario's, else the configured rule. The random rule draws for every agent in index
  // order, whether or not the scenario gives its heading, so a scenario's headings do not shift the others'.
  st.rng.seed(seed);
  for (int i = 0; i < n; ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    const AgentState& o = st.agents[std::size_t(a.opponent)];
    const bool pursuer = a.role == Role::kPursuer;
    const Vec3 pe = pursuer ? Vec3(o.kinematics.position - a.kinematics.position)
                            : Vec3(a.kinematics.position - o.kinematics.position);
    Heading initial;
    switch (g.initial_heading) {
      case InitialHeading::kChase: initial = level(pe); break;  // the pursuer faces the evader, the evader faces away
      case InitialHeading::kFacing: initial = level(pursuer ? pe : Vec3(-pe)); break;
      case InitialHeading::kPlusX: initial = {0.0, kPi / 2}; break;
      case InitialHeading::kRandom: {
        std::normal_distribution<double> normal;
        const Vec3 d(normal(st.rng), normal(st.rng), normal(st.rng));
        initial = heading_of(d.squaredNorm() > 0.0 ? d : Vec3::UnitX());
        break;
      }
    }
    a.kinematics.heading = scenario.start(i).heading.value_or(initial);
  }

  for (int i = 0; i < n; ++i) st.collider.place_agent(i, st.agents[std::size_t(i)].kinematics.position);
  check_overlaps(sim, st.collider, scenario, st.scratch.positions);
  if (sim.movers() != nullptr && g.mover_sensing == MoverSensing::kOctree) {
    st.moving_field = std::make_unique<world::MovingOccupancyField>(sim.arena());
    st.moving_field->set_time(*sim.movers(), 0.0);
  }
  for (int i = 0; i < n; ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    a.opponent = choose_opponent(st, i, rule_of(g, a.role));
    perceive_agent(sim, st, i);
  }
}

namespace {

CollisionEvent event_of(const SimState& st, int i, const world::Contact& c, double dt) {
  const AgentState& a = st.agents[std::size_t(i)];
  CollisionEvent e;
  e.step = st.step + 1;
  e.time = st.time + c.fraction * dt;
  e.agent = i;
  e.role = a.role;
  e.kind = c.kind;
  e.obstacle_id = c.obstacle_id;
  e.triangle = c.triangle;
  e.point = c.point;
  e.normal = c.normal;
  e.fraction = c.fraction;
  e.penetration = c.penetration;
  return e;
}

void record_collision(SimState& st, const CollisionEvent& e) {
  // Capacity 3n: at most a static or mover contact, a mover contact after a static stop, and an agent contact
  // per agent.
  st.events.collisions.push_back(e);
  st.events.agents[std::size_t(e.agent)].collided = true;
  ++st.agents[std::size_t(e.agent)].collisions;
  ++st.collisions;
  if (!st.first_collision) st.first_collision = e;
}

world::Contact contact_of(int agent, const world::MoverContact& m) {
  world::Contact c;
  c.agent = agent;
  c.kind = world::ObstacleKind::kMover;
  c.obstacle_id = m.mover;
  c.fraction = m.fraction;
  c.point = m.point;
  c.normal = m.normal;
  c.penetration = m.penetration;
  return c;
}

// Agent i moved (or tried to move) from `from` to `to` this step and the static sweep found `hit` (the
// collider holds its stop). The movers may touch it first; or, stopped by a static obstacle, it stands there
// for the rest of the step, where a mover may still run into it.
void collide_movers(const Sim& sim, SimState& st, int i, const Vec3& from, const Vec3& to,
                    const std::optional<world::Contact>& hit) {
  const double dt = sim.config().dt;
  const world::MoverTimeline& movers = *sim.movers();
  AgentState& a = st.agents[std::size_t(i)];
  KinematicState& k = st.scratch.next[std::size_t(i)];
  const double radius = a.config->radius;
  const auto m = movers.first_contact(from, to, radius, st.time, dt);
  if (m && (!hit || m->fraction < hit->fraction)) {
    const Vec3 delta = to - from;
    const double length = delta.norm();
    k.position = length > 0.0 ? Vec3(from + std::max(0.0, m->fraction - kAgentBackoff / length) * delta) : from;
    st.collider.place_agent(a.body, k.position);
    record_collision(st, event_of(st, i, contact_of(i, *m), dt));
    return;
  }
  if (!hit) return;
  k.position = st.collider.agent_position(a.body);  // stopped at the time of impact
  record_collision(st, event_of(st, i, *hit, dt));
  if (hit->fraction >= 1.0) return;
  const double rest = 1.0 - hit->fraction;
  if (auto late = movers.first_contact(k.position, k.position, radius, st.time + hit->fraction * dt, rest * dt)) {
    late->fraction = hit->fraction + late->fraction * rest;
    record_collision(st, event_of(st, i, contact_of(i, *late), dt));
  }
}

// Sweeps every colliding pair of agents over their segments of this step (after the obstacles stopped
// them), in index order; a pair that touches stops both at the time of impact.
void collide_agents(const Sim& sim, SimState& st) {
  const GameConfig& g = sim.config();
  const int n = st.agent_count();
  for (int i = 0; i < n; ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    for (int j = i + 1; j < n; ++j) {
      const AgentState& b = st.agents[std::size_t(j)];
      if (!b.active || !pair_collides(g.team.agent_collisions, a.role, b.role)) continue;
      KinematicState& na = st.scratch.next[std::size_t(i)];
      KinematicState& nb = st.scratch.next[std::size_t(j)];
      const Vec3 a0 = a.kinematics.position, b0 = b.kinematics.position;
      const double reach = a.config->radius + b.config->radius;
      const auto t = first_contact(a0, na.position, b0, nb.position, reach);
      if (!t) continue;
      const auto stop = [&](const Vec3& from, KinematicState& to) {
        const Vec3 delta = to.position - from;
        const double length = delta.norm();
        to.position = length > 0.0 ? Vec3(from + std::max(0.0, *t - kAgentBackoff / length) * delta) : from;
      };
      const Vec3 pa = a0 + *t * (na.position - a0), pb = b0 + *t * (nb.position - b0);
      stop(a0, na);
      stop(b0, nb);
      st.collider.place_agent(a.body, na.position);
      st.collider.place_agent(b.body, nb.position);
      const Vec3 ab = pb - pa;
      const double gap = ab.norm();
      const Vec3 normal = gap > 0.0 ? Vec3(-ab / gap) : Vec3(Vec3::UnitZ());  // from b towards a
      for (const auto& [self, other, n_self] : {std::tuple{i, j, normal}, std::tuple{j, i, Vec3(-normal)}}) {
        world::Contact c;
        c.agent = self;
        c.kind = world::ObstacleKind::kAgent;
        c.obstacle_id = other;
        c.fraction = *t;
        c.point = (self == i ? pa : pb) - st.agents[std::size_t(self)].config->radius * n_self;
        c.normal = n_self;
        c.penetration = *t == 0.0 ? std::max(0.0, reach - gap) : 0.0;
        record_collision(st, event_of(st, self, c, g.dt));
      }
    }
  }
}

// The static obstacles within the agent's hold_range, exactly (the collision world's closest points), for
// the guard's last resort. Queried only where the field cannot rule them out.
std::span<const world::NearPoint> near_obstacles(const Sim& sim, SimState& st, const AgentState& a) {
  const AgentConfig& c = *a.config;
  if (!c.guard.enabled) return {};
  const Vec3& p = a.kinematics.position;
  const double range = hold_range(c, sim.config().dt);
  if (!(sim.arena().clearance_lower_bound(p) < range)) return {};
  const int n = st.collider.obstacles_near(p, range, st.scratch.near);
  return std::span<const world::NearPoint>(st.scratch.near).first(std::size_t(n));
}

}  // namespace

const StepEvents& step(const Sim& sim, SimState& st, std::span<const Steering> commands) {
  assert(!st.done);
  assert(static_cast<int>(commands.size()) == st.agent_count());
  const GameConfig& g = sim.config();
  const int n = st.agent_count();
  StepEvents& ev = st.events;
  ev.collisions.clear();
  ev.captures.clear();
  ev.terminal = ev.truncated = false;

  // 1. Every active agent's heading and move, all from the state at t.
  const StateProbe probe(sim, st);
  for (int i = 0; i < n; ++i) {
    const StepProfile::Scope profiled(StepProfile::kConstraints);
    const AgentState& a = st.agents[std::size_t(i)];
    AgentEvents& e = ev.agents[std::size_t(i)];
    e.command = commands[std::size_t(i)];
    e.opponent = a.opponent;
    e.acted = a.active;
    e.collided = e.captured = e.terminal = false;
    e.captures = 0;
    if (!a.active) {
      e.reward = RewardTerms{};
      continue;
    }
    const AgentState& o = st.agents[std::size_t(a.opponent)];
    st.scratch.target_before[std::size_t(i)] = a.view.percept.target_distance;
    st.scratch.obstacle_before[std::size_t(i)] = a.view.percept.obstacle.distance;
    const ConstraintInputs in{*a.config,   a.role,   g.dt,   a.kinematics, o.kinematics.position, o.config->speed,
                              a.view.field, a.bounds, &probe, near_obstacles(sim, st, a)};
    Vec3 d;
    const Heading h = constrained_heading(in, e.command, &d);
    st.scratch.next[std::size_t(i)] = advance(a.kinematics, h, d, a.config->speed, g.dt, a.bounds);
  }

  // 2. Swept collisions with the map's obstacles, in index order: a hit stops the agent at the contact.
  const world::MoverTimeline* movers = sim.movers();
  for (int i = 0; i < n; ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    KinematicState& k = st.scratch.next[std::size_t(i)];
    const Vec3 from = a.kinematics.position, to = k.position;
    const auto c = [&] {
      const StepProfile::Scope profiled(StepProfile::kCollisions);
      return st.collider.move_agent(a.body, k.position);
    }();
    if (movers != nullptr) {
      const StepProfile::Scope profiled(StepProfile::kMovers);
      collide_movers(sim, st, i, from, to, c);
    } else if (c) {
      k.position = st.collider.agent_position(a.body);  // stopped at the time of impact
      record_collision(st, event_of(st, i, *c, g.dt));
    }
  }
  // 3. Agents with each other, when the configuration says they collide.
  if (g.team.agent_collisions != AgentCollisions::kNone) {
    const StepProfile::Scope profiled(StepProfile::kCollisions);
    collide_agents(sim, st);
  }

  // 4. Commit the moves.
  for (int i = 0; i < n; ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    const KinematicState& k = st.scratch.next[std::size_t(i)];
    a.path += (k.position - a.kinematics.position).norm();
    a.kinematics = k;
    ++a.steps;
  }
  st.step += 1;
  st.time = st.step * g.dt;

  // 5. Captures: a free evader within the capture distance of a pursuer leaves the game.
  for (int e = st.pursuers; e < n; ++e) {
    AgentState& ea = st.agents[std::size_t(e)];
    if (!ea.active) continue;
    int by = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int p = 0; p < st.pursuers; ++p) {
      const Vec3 pe = ea.kinematics.position - st.agents[std::size_t(p)].kinematics.position;
      // Far pairs are skipped on the squared distance; near ones compare the distance itself, as d_PE <= d_s.
      if (pe.squaredNorm() > st.scratch.capture_reach2) continue;
      const double d = pe.norm();
      if (d <= g.capture_distance && d < best) best = d, by = p;
    }
    if (by < 0) continue;
    ev.captures.push_back({st.step, st.time, by, e, best});
    ev.agents[std::size_t(e)].captured = true;
    ++ev.agents[std::size_t(by)].captures;
    ++st.agents[std::size_t(by)].captures;
    ea.captured_at = st.time;
    --st.free_evaders;
  }

  if (st.moving_field) {
    const StepProfile::Scope profiled(StepProfile::kMovers);
    st.moving_field->set_time(*sim.movers(), st.time);
  }

  // 6. New observations: every agent that took part in the step (a captured evader gets its final view).
  //    With one agent per role the opponents never change.
  const bool one_on_one = n == 2;
  for (int i = 0; i < n; ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    if (!ev.agents[std::size_t(i)].acted) continue;
    const StepProfile::Scope profiled(StepProfile::kObservation);
    if (!one_on_one && !ev.agents[std::size_t(i)].captured) a.opponent = choose_opponent(st, i, rule_of(g, a.role));
    perceive_agent(sim, st, i);
  }

  // 7. Rewards, each against the opponent the agent played during the step.
  const int captures = static_cast<int>(ev.captures.size());
  for (int i = 0; i < n; ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    AgentEvents& e = ev.agents[std::size_t(i)];
    if (!e.acted) continue;
    const AgentState& o = st.agents[std::size_t(e.opponent)];
    int success = 0;
    if (g.team.capture_reward == CaptureReward::kIndividual) {
      success = a.role == Role::kPursuer ? e.captures : (e.captured ? 1 : 0);
    } else {
      success = captures;  // every pursuer, and every evader that was still in the game
    }
    // The distance now to the opponent of the step; the percept already holds it when the opponent is
    // unchanged (the same expression, so the same bits).
    const double target_after = a.opponent == e.opponent ? a.view.percept.target_distance
                                                         : (o.kinematics.position - a.kinematics.position).norm();
    const RewardInputs in{st.scratch.target_before[std::size_t(i)],
                          target_after,
                          st.scratch.obstacle_before[std::size_t(i)],
                          a.view.percept.obstacle.distance,
                          success,
                          e.collided};
    {
      const StepProfile::Scope profiled(StepProfile::kRewards);
      e.reward = reward(a.role, a.config->reward, in, (a.config->speed + o.config->speed) * g.dt);
    }
    a.total_reward += e.reward.total;
    a.pinned_steps += a.view.percept.pinned;
    if (e.captured) a.active = false;
  }

  // 8. The end of the game.
  const bool all_captured = st.free_evaders == 0;
  const bool crash = g.collision == CollisionMode::kTerminate && !ev.collisions.empty();
  const bool timeout = st.step >= sim.max_steps();
  ev.terminal = all_captured || crash;
  ev.truncated = !ev.terminal && timeout;
  for (int i = 0; i < n; ++i) {
    AgentEvents& e = ev.agents[std::size_t(i)];
    if (e.acted) e.terminal = ev.terminal || e.captured;
  }
  st.done = ev.terminal || timeout;
  if (st.done) {
    if (all_captured) {
      st.outcome = Outcome::kCapture;
    } else if (crash) {
      // Named after the lowest-index agent that hit something: pursuers come first.
      int first = ev.collisions.front().agent;
      for (const CollisionEvent& c : ev.collisions) first = std::min(first, c.agent);
      st.outcome = st.agents[std::size_t(first)].role == Role::kPursuer ? Outcome::kPursuerCollision
                                                                        : Outcome::kEvaderCollision;
    } else {
      st.outcome = Outcome::kTimeout;
    }
  }
  return ev;
}

}  // namespace peg3d::game
