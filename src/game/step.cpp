// step(): one sample of dt as a sequence of named stages, in the manner of MuJoCo's mj_step -> mj_forward ->
// mj_fwdPosition. Each stage reads the state the stages before it left and writes only its own part of the
// state or its scratch; none allocates (the scratch is sized by reset()).
#include <cassert>
#include <cmath>
#include <limits>

#include "core/step_profile.hpp"
#include "game/constraints.hpp"
#include "game/sensing.hpp"
#include "game/knowledge.hpp"
#include "game/sim.hpp"
#include "game/views.hpp"
#include "sense/scan_map.hpp"
#include "geometry/sphere_sweep.hpp"

namespace peg3d::game {
namespace {

// After an agent-agent or agent-mover contact the agent is set back this far along its path (as
// CollisionWorld does for static obstacles), so it ends the step apart from what it touched.
constexpr double kAgentBackoff = 1e-3;  // m

// Agent i's contact `c` during this step, as the step's event.
CollisionEvent event_of(const SimState& st, int i, const world::Contact& c, double dt) {
  CollisionEvent e;
  static_cast<world::Contact&>(e) = c;
  e.agent = i;
  e.step = st.step + 1;
  e.time = st.time + c.fraction * dt;
  e.role = st.agents[std::size_t(i)].role;
  return e;
}

void record_collision(SimState& st, const CollisionEvent& e) {
  // Capacity 4n: at most a static or mover contact, a mover contact after a static stop, an agent contact and
  // (push mode) a solid body's per agent.
  st.events.collisions.push_back(e);
  st.events.agents[std::size_t(e.agent)].collided = true;
  ++st.agents[std::size_t(e.agent)].collisions;
  ++st.collisions;
  if (!st.first_collision) st.first_collision = e;
}

void count_give_up(SimState& st) {
  ++st.events.contact_give_ups;
  ++st.contact_give_ups;
}

// Where a move from `from` towards `to` stops at fraction t of the step, set back kAgentBackoff.
Vec3 stopped_at(const Vec3& from, const Vec3& to, double t) {
  const Vec3 delta = to - from;
  const double length = delta.norm();
  return length > 0.0 ? Vec3(from + std::max(0.0, t - kAgentBackoff / length) * delta) : from;
}

// The static obstacles within the agent's hold_range, exactly (the collision world's closest points), for
// the guard's last resort. Queried only where the field cannot rule them out.
std::span<const world::NearPoint> near_obstacles(const Sim& sim, SimState& st, const AgentState& a) {
  const AgentConfig& c = *a.config;
  // An agent that senses through its own map avoids only what it has seen: no exact last resort.
  if (!c.guard.enabled || c.observation.obstacles == ObstacleSource::kOwnMap) return {};
  const Vec3& p = a.kinematics.position;
  const double range = hold_range(c, sim.config().dt);
  if (!(sim.arena().clearance_lower_bound(p) < range)) return {};
  const int n = st.collider.obstacles_near(p, range, st.scratch.near);
  return std::span<const world::NearPoint>(st.scratch.near).first(std::size_t(n));
}

// Begin: the step's events start empty, with each agent's command and whether it is in the game.
void begin(SimState& st, std::span<const Steering> commands) {
  StepEvents& ev = st.events;
  ev.collisions.clear();
  ev.captures.clear();
  ev.pushes.clear();
  ev.contact_give_ups = 0;
  ev.terminal = ev.truncated = false;
  for (int i = 0; i < st.agent_count(); ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    AgentEvents& e = ev.agents[std::size_t(i)];
    e.command = commands[std::size_t(i)];
    e.opponent = a.opponent;
    e.acted = a.active;
    e.collided = e.captured = e.terminal = false;
    e.captures = 0;
    if (!a.active) e.reward = RewardTerms{};
  }
}

// Constrain: each active agent's heading for the step, its command through the constraint layer (bounded
// steering, motion space, obstacle guard), all from the state at t.
void constrain(const Sim& sim, SimState& st) {
  for (int i = 0; i < st.agent_count(); ++i) {
    const StepProfile::Scope profiled(StepProfile::kConstraints);
    const AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    const StateProbe probe(sim, st, i, a.nearest_mover);
    const AgentState& o = st.agents[std::size_t(a.opponent)];
    // The reward measures the true distance; with limited sight the percept holds the estimate's.
    st.scratch.target_before[std::size_t(i)] = st.sight_limited(i) ? (o.kinematics.position - a.kinematics.position).norm()
                                                                    : a.view.percept.target_distance;
    st.scratch.obstacle_before[std::size_t(i)] = a.view.percept.obstacle.distance;
    st.scratch.position_before[std::size_t(i)] = a.kinematics.position;
    // The motion space steers relative to where the agent takes its opponent to be (with limited sight, its view's).
    const Vec3& target = st.sight_limited(i) ? a.view.other.position : o.kinematics.position;
    const ConstraintInputs in{*a.config,   a.role,   sim.config().dt, a.kinematics, target, o.config->speed,
                              a.view.field, a.bounds, &probe,          near_obstacles(sim, st, a)};
    st.scratch.heading[std::size_t(i)] =
        constrained_heading(in, st.events.agents[std::size_t(i)].command, &st.scratch.direction[std::size_t(i)]);
  }
}

// Move: each active agent advances along its heading at its speed, clamped to the arena.
void move(const Sim& sim, SimState& st) {
  for (int i = 0; i < st.agent_count(); ++i) {
    const StepProfile::Scope profiled(StepProfile::kConstraints);
    const AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    st.scratch.next[std::size_t(i)] = advance(a.kinematics, st.scratch.heading[std::size_t(i)],
                                              st.scratch.direction[std::size_t(i)], a.config->speed,
                                              sim.config().dt, a.bounds);
  }
}

// Static collisions: each active agent's sphere swept along its move against the map's static obstacles
// (Bullet); the collision world stops it at its first contact, kept for the next stage.
void collide_static(SimState& st) {
  const StepProfile::Scope profiled(StepProfile::kCollisions);
  for (int i = 0; i < st.agent_count(); ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    st.scratch.hit[std::size_t(i)] = st.collider.move_agent(a.body, st.scratch.next[std::size_t(i)].position);
  }
}

// Agent i moved (or tried to move) from `from` to `to` this step and the static sweep found `hit` (the
// collider holds its stop). A mover may touch it first; or, stopped by a static obstacle, it stands there
// for the rest of the step, where a mover may still run into it.
void mover_contacts(const Sim& sim, SimState& st, int i, const Vec3& from, const Vec3& to,
                    const std::optional<world::Contact>& hit) {
  const double dt = sim.config().dt;
  const world::MoverTimeline& movers = *sim.movers();
  AgentState& a = st.agents[std::size_t(i)];
  KinematicState& k = st.scratch.next[std::size_t(i)];
  const double radius = a.config->radius;
  // The view of this instant may show that no mover comes near during the step: then there is nothing to find.
  const auto& c = a.mover_clearance;
  const bool clear = c.time == st.time && c.at == from && movers.clear_of_contact(c.distance, from, to, radius, st.time, dt);
  const auto m = clear ? std::nullopt : movers.first_contact(from, to, radius, st.time, dt);
  if (m && m->gave_up) count_give_up(st);
  if (m && (!hit || m->fraction < hit->fraction)) {
    k.position = stopped_at(from, to, m->fraction);
    st.collider.place_agent(a.body, k.position);
    record_collision(st, event_of(st, i, *m, dt));
    return;
  }
  if (!hit) return;
  k.position = st.collider.agent_position(a.body);  // stopped at the time of impact
  record_collision(st, event_of(st, i, *hit, dt));
  if (hit->fraction >= 1.0 || clear) return;  // clear: the sphere anywhere on its segment during the step
  const double rest = 1.0 - hit->fraction;
  if (auto late = movers.first_contact(k.position, k.position, radius, st.time + hit->fraction * dt, rest * dt)) {
    if (late->gave_up) count_give_up(st);
    late->fraction = hit->fraction + late->fraction * rest;
    record_collision(st, event_of(st, i, *late, dt));
  }
}

// Movers: with moving obstacles, whether one touches each agent before its static contact (conservative
// advancement on the timeline). Every obstacle contact of the step is recorded here, agents in index order,
// and each agent stops at its first.
void collide_movers(const Sim& sim, SimState& st) {
  for (int i = 0; i < st.agent_count(); ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    const std::optional<world::Contact>& hit = st.scratch.hit[std::size_t(i)];
    if (sim.movers() != nullptr) {
      const StepProfile::Scope profiled(StepProfile::kMovers);
      const Vec3 to = st.scratch.next[std::size_t(i)].position;
      mover_contacts(sim, st, i, a.kinematics.position, to, hit);
    } else if (hit) {
      st.scratch.next[std::size_t(i)].position = st.collider.agent_position(a.body);  // stopped at the time of impact
      record_collision(st, event_of(st, i, *hit, sim.config().dt));
    }
  }
}

// Agent collisions: every colliding pair swept over their segments of this step (after the obstacles
// stopped them), in index order; a pair that touches stops both at the time of impact.
void collide_agents(const Sim& sim, SimState& st) {
  const GameConfig& g = sim.config();
  if (g.team.agent_collisions == AgentCollisions::kNone) return;
  const StepProfile::Scope profiled(StepProfile::kCollisions);
  const int n = st.agent_count();
  for (int i = 0; i < n; ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    for (int j = i + 1; j < n; ++j) {
      const AgentState& b = st.agents[std::size_t(j)];
      if (!b.active || !g.team.collide(a.role, b.role)) continue;
      KinematicState& na = st.scratch.next[std::size_t(i)];
      KinematicState& nb = st.scratch.next[std::size_t(j)];
      const Vec3 a0 = a.kinematics.position, b0 = b.kinematics.position;
      const double reach = a.config->radius + b.config->radius;
      const auto t = first_contact(a0, na.position, b0, nb.position, reach);
      if (!t) continue;
      const Vec3 pa = a0 + *t * (na.position - a0), pb = b0 + *t * (nb.position - b0);
      na.position = stopped_at(a0, na.position, *t);
      nb.position = stopped_at(b0, nb.position, *t);
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

// Push: in push mode the run's own world sweeps every active agent along its move in physics substeps; the
// pushable bodies it meets are pushed (StepEvents::pushes) and a solid one stops it (a collision, recorded
// after the step's other contacts).
void push_bodies(const Sim& sim, SimState& st) {
  if (!st.push) return;
  const StepProfile::Scope profiled(StepProfile::kMovers);
  const int n = st.agent_count();
  for (int i = 0; i < n; ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) st.push->remove_agent(i);
    st.scratch.from[std::size_t(i)] = a.kinematics.position;
    st.scratch.to[std::size_t(i)] = a.active ? st.scratch.next[std::size_t(i)].position : a.kinematics.position;
  }
  st.scratch.touches.clear();
  st.push->advance(st.scratch.from, st.scratch.to, st.scratch.touches);
  const double dt = sim.config().dt;
  for (const world::Contact& t : st.scratch.touches) {
    if (t.pushed) {
      PushEvent p;
      static_cast<world::Contact&>(p) = t;
      p.step = st.step + 1;
      p.time = st.time + t.fraction * dt;
      st.events.pushes.push_back(p);
      continue;
    }
    KinematicState& k = st.scratch.next[std::size_t(t.agent)];
    k.position = st.scratch.to[std::size_t(t.agent)];
    st.collider.place_agent(st.agents[std::size_t(t.agent)].body, k.position);
    record_collision(st, event_of(st, t.agent, t, dt));
  }
}

// Commit: every active agent takes its (possibly stopped) move; the clock advances by dt.
void commit(const Sim& sim, SimState& st) {
  for (int i = 0; i < st.agent_count(); ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    if (!a.active) continue;
    const KinematicState& k = st.scratch.next[std::size_t(i)];
    a.path += (k.position - a.kinematics.position).norm();
    a.kinematics = k;
    ++a.steps;
  }
  st.step += 1;
  st.time = st.step * sim.config().dt;
}

// Captures: a free evader within the capture distance of a pursuer leaves the game, captured by the nearest.
void capture(const Sim& sim, SimState& st) {
  const double d_s = sim.config().capture_distance;
  StepEvents& ev = st.events;
  for (int e = st.pursuers; e < st.agent_count(); ++e) {
    AgentState& ea = st.agents[std::size_t(e)];
    if (!ea.active) continue;
    int by = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int p = 0; p < st.pursuers; ++p) {
      const Vec3 pe = ea.kinematics.position - st.agents[std::size_t(p)].kinematics.position;
      // Far pairs are skipped on the squared distance; near ones compare the distance itself, as d_PE <= d_s.
      if (pe.squaredNorm() > st.scratch.capture_reach2) continue;
      const double d = pe.norm();
      if (d <= d_s && d < best) best = d, by = p;
    }
    if (by < 0) continue;
    ev.captures.push_back({st.step, st.time, by, e, best});
    ev.agents[std::size_t(e)].captured = true;
    ++ev.agents[std::size_t(by)].captures;
    ++st.agents[std::size_t(by)].captures;
    ea.captured_at = st.time;
    --st.free_evaders;
  }
}

// Observe: the octree that follows the movers comes to the new time, then every agent that took part in the
// step gets its new view (a captured evader its final one). With one agent per role the opponents never
// change.
void observe(const Sim& sim, SimState& st) {
  if (st.moving_field) {
    const StepProfile::Scope profiled(StepProfile::kMovers);
    st.moving_field->set_time(*sim.movers(), st.time);
  }
  look(sim, st);
  snapshot_teams(st);
  const bool one_on_one = st.agent_count() == 2;
  for (int i = 0; i < st.agent_count(); ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    const AgentEvents& e = st.events.agents[std::size_t(i)];
    if (!e.acted) continue;
    const StepProfile::Scope profiled(StepProfile::kObservation);
    if (!one_on_one && !e.captured) a.opponent = choose_opponent(st, i, sim.config().team.opponent_rule(a.role));
    update_view(sim, st, i);
  }
}

// Rewards: each agent's terms against the opponent it played during the step (APF, eq. 15-18), and its
// totals; a captured evader leaves the game here.
void reward_all(const Sim& sim, SimState& st) {
  const GameConfig& g = sim.config();
  StepEvents& ev = st.events;
  const int captures = static_cast<int>(ev.captures.size());
  for (int i = 0; i < st.agent_count(); ++i) {
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
    const double target_after = a.opponent == e.opponent && !st.sight_limited(i)
                                    ? a.view.percept.target_distance
                                    : (o.kinematics.position - a.kinematics.position).norm();
    {
      const StepProfile::Scope profiled(StepProfile::kRewards);
      // An own map whose obstacles the step's scan changed: d_O before the move measured again in the map as it
      // is now, so that the repulsion term (exponential in the change of d_O) rewards the move, not what the scan
      // revealed.
      const bool rescanned = a.config->observation.obstacles == ObstacleSource::kOwnMap &&
                             st.sensing.map_step[std::size_t(i)] == st.step &&
                             st.map(i)->last_insert_moved_obstacles_within(st.scratch.position_before[std::size_t(i)],
                                                                           st.scratch.obstacle_before[std::size_t(i)]);
      const double obstacle_before = rescanned ? own_map_obstacle_distance(sim, st, i, st.scratch.position_before[std::size_t(i)])
                                               : st.scratch.obstacle_before[std::size_t(i)];
      const RewardInputs in{st.scratch.target_before[std::size_t(i)],
                            target_after,
                            obstacle_before,
                            a.view.percept.obstacle.distance,
                            success,
                            e.collided};
      e.reward = reward(a.role, a.config->reward, in, (a.config->speed + o.config->speed) * g.dt);
    }
    a.total_reward += e.reward.total;
    a.pinned_steps += a.view.percept.pinned;
    if (e.captured) a.active = false;
  }
}

// End: whether the game is over (every evader captured, a terminating collision) or truncated (the time
// limit), and how it ended.
void end(const Sim& sim, SimState& st) {
  StepEvents& ev = st.events;
  const bool all_captured = st.free_evaders == 0;
  const bool crash = sim.config().collision == CollisionMode::kTerminate && !ev.collisions.empty();
  const bool timeout = st.step >= sim.max_steps();
  ev.terminal = all_captured || crash;
  ev.truncated = !ev.terminal && timeout;
  for (AgentEvents& e : ev.agents) {
    if (e.acted) e.terminal = ev.terminal || e.captured;
  }
  st.done = ev.terminal || timeout;
  if (!st.done) return;
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

}  // namespace

const StepEvents& step(const Sim& sim, SimState& st, std::span<const Steering> commands) {
  assert(!st.done);
  check_commands(st, commands);  // before anything changes: a refused step leaves the state as it was
  begin(st, commands);
  constrain(sim, st);
  move(sim, st);
  collide_static(st);
  collide_movers(sim, st);
  collide_agents(sim, st);
  push_bodies(sim, st);
  commit(sim, st);
  capture(sim, st);
  scan_due(sim, st);
  observe(sim, st);
  reward_all(sim, st);
  end(sim, st);
  return st.events;
}

}  // namespace peg3d::game
