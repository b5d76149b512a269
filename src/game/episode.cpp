#include "game/episode.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "sense/scan_map.hpp"

namespace peg3d::game {

EpisodeResult summarize(const SimState& st) {
  EpisodeResult r;
  r.outcome = st.outcome;
  r.steps = st.step;
  r.duration = st.time;
  r.collisions = st.collisions;
  r.contact_give_ups = st.contact_give_ups;
  r.first_collision = st.first_collision;
  r.pursuers = st.pursuers;
  r.evaders = st.evaders();
  double best = std::numeric_limits<double>::infinity();
  for (int e = st.pursuers; e < st.agent_count(); ++e) {
    const AgentState& ea = st.agents[std::size_t(e)];
    // Evaders in the game during the last step: the free ones and those captured by it.
    if (!ea.active && ea.captured_at != st.time) continue;
    for (int p = 0; p < st.pursuers; ++p) {
      best = std::min(best, (ea.kinematics.position - st.agents[std::size_t(p)].kinematics.position).norm());
    }
  }
  r.final_distance = std::isfinite(best) ? best : 0.0;
  for (const AgentState& a : st.agents) {
    const bool p = a.role == Role::kPursuer;
    (p ? r.pursuer_path : r.evader_path) += a.path;
    (p ? r.pursuer_return : r.evader_return) += a.total_reward;
    (p ? r.pursuer_pinned_steps : r.evader_pinned_steps) += a.pinned_steps;
    (p ? r.pursuer_agent_steps : r.evader_agent_steps) += a.steps;
    if (!p && a.captured_at >= 0.0) {
      ++r.captures;
      r.capture_time_sum += a.captured_at;
      r.last_capture_time = std::max(r.last_capture_time, a.captured_at);
    }
  }
  r.pursuer_path /= r.pursuers;
  r.evader_path /= r.evaders;
  r.pursuer_return /= r.pursuers;
  r.evader_return /= r.evaders;
  return r;
}

std::vector<AgentSummary> agent_summaries(const SimState& st) {
  std::vector<AgentSummary> out;
  out.reserve(st.agents.size());
  for (const AgentState& a : st.agents) {
    out.push_back({a.role, a.rank, a.path, a.total_reward, a.steps,
                   a.steps > 0 ? static_cast<double>(a.pinned_steps) / a.steps : 0.0, a.collisions, a.captures,
                   a.captured_at});
  }
  return out;
}

void Trace::reserve(int max_steps, int agent_count, int values, std::size_t map_flip_count) {
  const std::size_t frames_needed = std::size_t(max_steps) + 1;
  roles.reserve(std::size_t(agent_count));
  times.reserve(frames_needed);
  frames.reserve(frames_needed * std::size_t(agent_count));
  collisions.reserve(frames_needed * std::size_t(agent_count) * 3);
  captures.reserve(std::size_t(agent_count));
  if (values > 0) {
    slot_first.reserve(std::size_t(agent_count) + 1);
    readings.reserve(frames_needed * std::size_t(values));
    echoes.reserve(frames_needed * std::size_t(values));
    scan_frames.reserve(frames_needed * std::size_t(agent_count));
  }
  map_flips.reserve(map_flip_count);
}

void Trace::reserve(const Sim& sim, const world::Scenario& scenario, std::size_t map_flip_count) {
  const int n = scenario.agents(), p = static_cast<int>(scenario.pursuers.size());
  int values = 0;
  std::size_t slots = 0;
  for (int i = 0; i < n; ++i) {
    for (const sense::Sensor* s : sim.sensors(role_at(i, p), rank_at(i, p))) values += s->values(n), ++slots;
  }
  reserve(sim.max_steps(), n, values, map_flip_count);
  const std::size_t frames_needed = std::size_t(sim.max_steps()) + 1;
  value_first.reserve(slots + 1);
  scan_frames.reserve(frames_needed * slots);
}

std::string agent_label(const Trace& trace, int i) {
  const Role role = trace.roles[std::size_t(i)];
  int rank = 0;
  for (int j = 0; j < i; ++j) rank += trace.roles[std::size_t(j)] == role;
  return agent_label(role, rank);
}

void Trace::clear() {
  agents = 0;
  roles.clear();
  times.clear();
  frames.clear();
  collisions.clear();
  captures.clear();
  pushes.clear();
  body_poses.clear();
  movers = 0;
  slot_first.clear();
  value_first.clear();
  readings.clear();
  echoes.clear();
  scan_frames.clear();
  map_flips.clear();
}

void Trace::record(const SimState& st, bool after_step) {
  if (!after_step) {
    clear();
    agents = st.agent_count();
    for (const AgentState& a : st.agents) roles.push_back(a.role);
    slot_first.assign(st.sensing.first.begin(), st.sensing.first.end());
    value_first.clear();
    if (!slot_first.empty()) {
      for (int k = 0; k < slot_first.back(); ++k) value_first.push_back(st.sensing.slots[std::size_t(k)].begin);
      value_first.push_back(int(st.sensing.values.size()));
    }
  }
  assert(agents == st.agent_count());
  times.push_back(st.time);
  for (int i = 0; i < st.agent_count(); ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    AgentFrame f;
    f.state = a.kinematics;
    f.percept = a.view.percept;
    f.active = a.active;
    if (st.sight_limited(i)) {
      f.opponent = a.opponent;
      f.sees = a.view.other_visible;
      f.estimate = a.view.other.position;
    }
    if (after_step) {
      const AgentEvents& e = st.events.agents[std::size_t(i)];
      f.command = e.command;
      f.reward = e.reward.total;
      f.active = e.acted;  // a captured evader is shown at its capture
    }
    frames.push_back(f);
  }
  if (!slot_first.empty()) record_sensing(st, after_step);
  if (st.push) {
    movers = st.push->movers();
    for (int m = 0; m < movers; ++m) body_poses.push_back(st.push->pose(m));
  }
  if (after_step) {
    collisions.insert(collisions.end(), st.events.collisions.begin(), st.events.collisions.end());
    captures.insert(captures.end(), st.events.captures.begin(), st.events.captures.end());
    pushes.insert(pushes.end(), st.events.pushes.begin(), st.events.pushes.end());
  }
}

void Trace::record_sensing(const SimState& st, bool after_step) {
  const int frame = frame_count() - 1;
  for (const double r : st.sensing.values) readings.push_back(float(r));
  echoes.insert(echoes.end(), st.sensing.echo.begin(), st.sensing.echo.end());
  for (int k = 0; k < slot_first.back(); ++k) scan_frames.push_back(st.sensing.readings[std::size_t(k)].step);
  for (int i = 0; i < agents; ++i) {
    const sense::ScanMap* map = st.map(i);
    if (map == nullptr) continue;
    if (!after_step) {  // the map as the episode starts: the reset's scan, and with map.persist earlier episodes'
      map->for_each_known([&](const sense::CellKey& key, float log_odds) {
        if (log_odds > 0.0f) map_flips.push_back({frame, i, map->centre(key), true});
      });
    } else if (st.sensing.map_step[std::size_t(i)] == st.step) {  // a scan went into it in this step
      map->for_each_flip([&](const sense::CellKey& key, bool occupied) {
        map_flips.push_back({frame, i, map->centre(key), occupied});
      });
    }
  }
}

Trace::SlotReadings Trace::slot_readings(int i, int k) const {
  SlotReadings r;
  const auto slot = std::size_t(slot_first[std::size_t(i)] + k);
  const auto b = std::size_t(value_first[slot]), e = std::size_t(value_first[slot + 1]);
  r.size = int(e - b);
  const auto per_frame = std::size_t(values()), slots = std::size_t(slot_first.back());
  for (int f = 0; f < frame_count(); ++f) {
    const std::size_t at = std::size_t(f) * per_frame;
    r.values.insert(r.values.end(), readings.begin() + long(at + b), readings.begin() + long(at + e));
    r.echo.insert(r.echo.end(), echoes.begin() + long(at + b), echoes.begin() + long(at + e));
    r.scan_frames.push_back(scan_frames[std::size_t(f) * slots + slot]);
  }
  return r;
}

const StepEvents& step_naming_file(const Sim& sim, SimState& st, std::span<const Steering> commands,
                                   std::span<Policy* const> policies) {
  try {
    return step(sim, st, commands);
  } catch (const CommandError& e) {
    if (e.agent() >= 0 && static_cast<std::size_t>(e.agent()) < policies.size()) {
      const Policy* p = policies[std::size_t(e.agent())];
      if (p != nullptr && !p->file().empty()) throw e.played_by(p->file());
    }
    throw;
  }
}

void begin_playing(const Sim& sim, SimState& st, int i, Policy& policy, bool learning) {
  policy.begin_episode(observe(st, i), learning);
  AgentState& a = st.agents[std::size_t(i)];
  a.config = policy.scripted() ? &sim.scripted_config(a.role, a.rank) : &sim.config().agent(a.role, a.rank);
}

EpisodeResult play(const Sim& sim, SimState& st, const world::Scenario& scenario, std::span<Policy* const> policies,
                   bool learning, std::uint64_t seed, Trace* trace) {
  reset(sim, st, scenario, seed);
  const int n = st.agent_count();
  assert(static_cast<int>(policies.size()) == n);
  for (int i = 0; i < n; ++i) begin_playing(sim, st, i, *policies[std::size_t(i)], learning);
  if (trace) trace->record(st, false);

  // Commands of agents out of the game are ignored by step(); the buffer is the state's, so no allocation.
  std::vector<Steering>& commands = st.scratch.commands;
  commands.assign(std::size_t(n), Steering{});
  while (!st.done) {
    for (int i = 0; i < n; ++i) {
      if (st.agents[std::size_t(i)].active) commands[std::size_t(i)] = policies[std::size_t(i)]->act(observe(st, i));
    }
    const StepEvents& ev = step_naming_file(sim, st, commands, policies);
    if (learning) {
      for (int i = 0; i < n; ++i) {
        const AgentEvents& e = ev.agents[std::size_t(i)];
        // The time limit truncates the episode; it is not a terminal state of the game, so learners bootstrap.
        if (e.acted) policies[std::size_t(i)]->learn(e.reward.total, observe(st, i), e.terminal);
      }
    }
    if (trace) trace->record(st, true);
  }
  return summarize(st);
}

Steering TimedCommands::act(const AgentView& view) {
  Steering u;
  // Half a step of slack, so a command written for t = 1.0 applies at the step starting at 1.0 s whatever the
  // rounding of k * dt.
  for (const TimedCommand& c : commands_) {
    if (c.time > view.time + 0.5 * view.dt) break;
    u = c.command;
  }
  return u;
}

Steering WaypointFollower::act(const AgentView& view) {
  const double reach = std::max(view.self_speed * view.dt, 1e-9);
  while (next_ < waypoints_.size()) {
    const bool timed_next = next_ + 1 < waypoints_.size() && waypoints_[next_ + 1].time >= 0.0;
    if (timed_next && view.time + 0.5 * view.dt >= waypoints_[next_ + 1].time) {
      ++next_;  // the next waypoint's time has come
      continue;
    }
    if (!timed_next && next_ + 1 < waypoints_.size() && (waypoints_[next_].point - view.self.position).norm() <= reach) {
      ++next_;  // reached: on to the next
      continue;
    }
    break;
  }
  if (next_ >= waypoints_.size()) return {};
  const Vec3 d = waypoints_[next_].point - view.self.position;
  if (d.norm() <= 1e-12) return {};
  const AngleErrors e = angle_errors(view.self.heading, d);
  return {e.azimuth, e.elevation};
}

}  // namespace peg3d::game
