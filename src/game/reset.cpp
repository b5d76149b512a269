// reset(): a state put at a scenario's start, its agents placed and checked, headed and given their first
// views.
#include <cmath>
#include <random>

#include "game/observation.hpp"
#include "game/sensing.hpp"
#include "game/knowledge.hpp"
#include "game/sim.hpp"
#include "game/starts.hpp"
#include "game/views.hpp"

namespace peg3d::game {
namespace {

Heading level(const Vec3& d) {
  return {d.x() == 0.0 && d.y() == 0.0 ? 0.0 : std::atan2(d.y(), d.x()), kPi / 2};
}

// Sizes the state for n agents (nothing is allocated for a scenario no larger than before) and clears the
// run's clock, events and totals.
void clear_for(SimState& st, int n, int pursuers, const GameConfig& g) {
  const auto size = static_cast<std::size_t>(n);
  st.pursuers = pursuers;
  st.agents.resize(size);
  st.scratch.heading.resize(size);
  st.scratch.direction.resize(size);
  st.scratch.next.resize(size);
  st.scratch.hit.resize(size);
  st.scratch.target_before.resize(size);
  st.scratch.obstacle_before.resize(size);
  st.scratch.position_before.resize(size);
  st.scratch.positions.resize(size);
  st.events.agents.assign(size, AgentEvents{});
  st.events.collisions.clear();
  st.events.collisions.reserve(4 * size);
  st.events.captures.clear();
  st.events.captures.reserve(size);
  st.events.pushes.clear();
  st.scratch.from.resize(size);
  st.scratch.to.resize(size);
  st.events.terminal = st.events.truncated = false;
  st.time = 0.0;
  st.step = 0;
  st.free_evaders = n - pursuers;
  st.done = false;
  st.outcome = Outcome::kTimeout;
  st.first_collision.reset();
  st.collisions = 0;
  st.contact_give_ups = st.events.contact_give_ups = 0;
  // A margin above d_s^2 so that rounding can never skip a pair whose distance is <= d_s.
  st.scratch.capture_reach2 = g.capture_distance * g.capture_distance * (1.0 + 1e-9) + 1e-12;
  while (st.collider.agent_count() < n) st.collider.add_agent(1.0);
}

// Each agent's heading: the scenario's, else the configured rule. The random rule draws for every agent in
// index order, whether or not the scenario gives its heading, so a scenario's headings do not shift the
// others'.
void initial_headings(const GameConfig& g, SimState& st, const world::Scenario& scenario, std::uint64_t seed) {
  st.rng.seed(seed);
  for (int i = 0; i < st.agent_count(); ++i) {
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
}

}  // namespace

void reset(const Sim& sim, SimState& st, const world::Scenario& scenario, std::uint64_t seed) {
  check_counts(scenario);
  const GameConfig& g = sim.config();
  const int n = scenario.agents(), p = static_cast<int>(scenario.pursuers.size());
  clear_for(st, n, p, g);
  start_positions(sim.arena(), g, scenario, st.scratch.positions);
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
  initial_headings(g, st, scenario, seed);
  for (int i = 0; i < n; ++i) st.collider.place_agent(i, st.agents[std::size_t(i)].kinematics.position);
  check_start(sim.arena(), g, sim.movers(), st.collider, scenario, st.scratch.positions);
  if (sim.pushes()) {
    st.push = std::make_unique<world::PushWorld>(sim.arena().map(), sim.arena().physics_shapes(), sim.substeps());
    for (int i = 0; i < n; ++i) st.push->add_agent(st.agents[std::size_t(i)].config->radius, st.agents[std::size_t(i)].kinematics.position);
    st.scratch.touches.reserve(st.push->max_touches());
    st.events.pushes.reserve(st.push->max_touches());
  } else {
    st.push.reset();
  }
  if (sim.movers() != nullptr && g.mover_sensing == MoverSensing::kOctree) {
    st.moving_field = std::make_unique<world::MovingOccupancyField>(sim.arena());
    st.moving_field->set_time(*sim.movers(), 0.0);
  }
  attach_observation_writer(sim, st);
  prepare_sensing(sim, st, seed);
  for (int i = 0; i < n; ++i) scan_all(sim, st, i);
  prepare_sight(sim, st);
  look(sim, st);
  snapshot_teams(st);
  for (int i = 0; i < n; ++i) {
    AgentState& a = st.agents[std::size_t(i)];
    a.opponent = choose_opponent(st, i, g.team.opponent_rule(a.role));
    update_view(sim, st, i);
  }
}

}  // namespace peg3d::game
