#include "game/views.hpp"

#include <algorithm>

#include "core/step_profile.hpp"

namespace peg3d::game {

ObstacleSense sense_obstacle(const Sim& sim, const SimState& st, const Vec3& p, double reach, int* mover) {
  const world::NearestObstacle n = st.moving_field ? st.moving_field->nearest(p) : sim.arena().nearest_shape(p);
  if (const world::MoverTimeline* movers = sim.movers(); movers != nullptr && !st.moving_field) {
    // Moving obstacles where they are now, exactly: those nearer than the field's obstacle and within reach.
    const double cap = std::min(n.distance, reach);
    world::MoverPoint m = movers->nearest(p, st.time, cap, mover ? *mover : -1);
    if (mover) *mover = m.mover;
    if (st.push) {
      // Push mode: the run's own dynamic bodies where they are now.
      const world::MoverPoint d = st.push->nearest(p, m.mover >= 0 ? m.distance : cap);
      if (d.mover >= 0 && (m.mover < 0 || d.distance < m.distance || (d.distance == m.distance && d.mover < m.mover))) m = d;
    }
    if (m.mover >= 0) return {m.distance, m.point, true};
  }
  return {n.distance, n.point, n.found};
}

ObstacleSense sense_own_map(const Sim& sim, const SimState& st, int i, const Vec3& p) {
  const StepProfile::Scope profiled(StepProfile::kMapQuery);
  const sense::OccupiedPoint n = st.map(i)->nearest_occupied(p, sim.arena().max_distance());
  return {n.distance, n.point, n.found};
}

double own_map_obstacle_distance(const Sim& sim, const SimState& st, int i, const Vec3& p) {
  const AgentState& a = st.agents[std::size_t(i)];
  KinematicState self = a.kinematics;
  self.position = p;
  return perceive(a.role, a.config->observation, a.config->radius, self, st.agents[std::size_t(a.opponent)].kinematics, sense_own_map(sim, st, i, p),
                  sim.arena().bounds(), sim.arena().max_distance())
      .obstacle.distance;
}

void snapshot_teams(SimState& st) {
  st.team_states.resize(st.agents.size());
  for (std::size_t i = 0; i < st.agents.size(); ++i) st.team_states[i] = st.agents[i].kinematics;
}

void update_view(const Sim& sim, SimState& st, int i) {
  AgentState& a = st.agents[std::size_t(i)];
  const AgentState& o = st.agents[std::size_t(a.opponent)];
  AgentView& v = a.view;
  v.role = a.role;
  v.index = i;
  v.opponent = a.opponent;
  v.self = a.kinematics;
  v.rank = a.rank;
  const auto [first, end] = st.of_role(a.role);
  v.team = std::span<const KinematicState>(st.team_states).subspan(std::size_t(first), std::size_t(end - first));
  // With limited sight, the opponent as the agent knows it (SimState::known_state), and how it knows it.
  v.other = st.known_state(i, a.opponent);
  v.other_visible = st.sees(i, a.opponent);
  v.other_age = st.sighting_age(i, a.opponent);
  v.probe = st.sight_limited(i) && a.config->observation.obstacles == ObstacleSource::kWorld ? st.sight.probes[std::size_t(i)].get() : nullptr;
  v.self_speed = a.config->speed;
  v.other_speed = o.config->speed;
  v.dt = sim.config().dt;
  v.time = st.time;
  v.arena = sim.arena().bounds();
  v.sensors = st.readings(i);
  v.observation = st.observation_writer.get();
  const bool own_map = a.config->observation.obstacles == ObstacleSource::kOwnMap;
  v.field = own_map ? sense_own_map(sim, st, i, a.kinematics.position)
                    : sense_obstacle(sim, st, a.kinematics.position, std::numeric_limits<double>::infinity(), &a.nearest_mover);
  // Exactly sensed, the field's distance bounds every mover's from below (sense_obstacle): kept for the step.
  const bool exact = sim.movers() != nullptr && !st.moving_field && !own_map;
  a.mover_clearance = {a.kinematics.position, exact ? st.time : -1.0, v.field.distance};
  v.percept = perceive(a.role, a.config->observation, a.config->radius, a.kinematics, v.other, v.field, sim.arena().bounds(),
                       sim.arena().max_distance());
}

}  // namespace peg3d::game
