#include "game/sim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/config_fields.hpp"
#include "game/starts.hpp"
#include "world/map/map_spec.hpp"

// A configuration's per-agent lists are bounded by the most agents a role can have.
static_assert(peg3d::config::kMaxSections == std::size_t(peg3d::world::kMaxAgentsPerRole));

namespace peg3d::game {

CommandError::CommandError(int step, int agent, std::string who, std::string detail)
    : CommandError(step, agent, -1, std::move(who), std::move(detail), {}) {}

CommandError::CommandError(int step, int agent, int game, std::string who, std::string detail, std::filesystem::path file)
    : InputError(file, 0, "",
                 fmt::format("{}step {}: {}{}{}; nothing was stepped", game >= 0 ? fmt::format("game {}: ", game) : "",
                             step, who, who.empty() ? "" : (file.empty() ? ": " : ", played by this policy file: "),
                             detail)),
      step_(step),
      agent_(agent),
      game_(game),
      who_(std::move(who)),
      detail_(std::move(detail)) {}

CommandError CommandError::played_by(const std::filesystem::path& file) const {
  return CommandError(step_, agent_, game_, who_, detail_, file);
}

CommandError CommandError::in_game(int game) const { return CommandError(step_, agent_, game, who_, detail_, file()); }

void check_command(const SimState& st, int i, const Steering& u) {
  if (std::isfinite(u.d_alpha) && std::isfinite(u.d_theta)) return;
  const AgentState& a = st.agents[std::size_t(i)];
  if (!a.active) return;  // ignored by the step
  throw CommandError(st.step + 1, i, fmt::format("agent {} ({} {})", i, to_string(a.role), a.rank),
                     fmt::format("steering command ({}, {}) rad is not finite", u.d_alpha, u.d_theta));
}

void check_command_count(const SimState& st, std::size_t count) {
  throw CommandError(st.step + 1, -1, "", fmt::format("{} steering commands for {} agents", count, st.agent_count()));
}

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::kCapture: return "capture";
    case Outcome::kTimeout: return "timeout";
    case Outcome::kPursuerCollision: return "pursuer-collision";
    case Outcome::kEvaderCollision: return "evader-collision";
  }
  return "?";
}

int choose_opponent(const SimState& st, int i, OpponentChoice rule) {
  const AgentState& a = st.agents[std::size_t(i)];
  const auto [lo, hi] = st.of_role(opposing(a.role));
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
    // With limited sight, where the agent takes the opponent to be.
    const double d2 = (st.sight_limited(i) ? st.known_state(i, j).position - a.kinematics.position
                                           : o.kinematics.position - a.kinematics.position)
                          .squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = j;
  }
  return best >= 0 ? best : a.opponent;
}

Sim::Sim(std::shared_ptr<const world::Arena> arena, GameConfig config)
    : arena_(std::move(arena)), config_(std::make_shared<const GameConfig>(std::move(config))) {
  config_->validate();
  max_steps_ = config_->max_steps();
  // Every agent's configuration as scripted_agent makes it, kept once: classic players' agents point at it.
  GameConfig scripted = *config_;
  bool differs = false;
  const auto script = [&](AgentConfig& a) {
    differs = differs || a.motion_space;
    a = scripted_agent(a, a.policy);
  };
  script(scripted.pursuer);
  script(scripted.evader);
  for (AgentConfig& a : scripted.pursuers) script(a);
  for (AgentConfig& a : scripted.evaders) script(a);
  scripted_ = differs ? std::make_shared<const GameConfig>(std::move(scripted)) : config_;
  const world::MapSpec& map = arena_->map();
  if (!map.movers.empty()) {
    const double substeps = config_->dt * map.physics.rate_hz;
    if (std::abs(substeps - std::round(substeps)) > 1e-9 * std::max(1.0, substeps) || std::round(substeps) < 1.0) {
      throw world::MapError(map.source, map.physics.line, "physics.rate_hz",
                            fmt::format("{} Hz does not divide the game step dt = {} s into whole substeps",
                                        map.physics.rate_hz, config_->dt));
    }
    // Push mode: every run simulates the dynamic bodies itself; the shared timeline keeps the scripted movers.
    pushes_ = config_->mover_dynamics == MoverDynamics::kPush &&
              std::any_of(map.movers.begin(), map.movers.end(), [](const world::MoverSpec& m) { return !m.kinematic(); });
    if (pushes_ && config_->mover_sensing != MoverSensing::kExact) {
      throw InvalidParameter("mover_dynamics", "push", "needs mover_sensing = exact (the octree follows the shared timeline)");
    }
    substeps_ = static_cast<int>(std::lround(substeps));
    movers_ = arena_->movers_until(config_->time_limit + config_->dt, !pushes_);
  }
  std::vector<std::pair<std::string, const AgentConfig*>> agents{{"pursuer", &config_->pursuer}, {"evader", &config_->evader}};
  for (const auto& [name, list] : {std::pair{"pursuers", &config_->pursuers}, std::pair{"evaders", &config_->evaders}}) {
    for (std::size_t k = 0; k < list->size(); ++k) agents.emplace_back(fmt::format("{}.{}", name, k), &(*list)[k]);
  }
  std::vector<std::pair<std::string, const AgentConfig*>> carrying;
  for (const auto& [name, a] : agents) {
    if (sense::make_sensors(a->sensors).empty()) continue;
    carrying.emplace_back(name, a);
    // An agent's map covers the arena: refused here, before any run, when it would not fit.
    const Vec3 &lo = arena_->bounds().lo, &hi = arena_->bounds().hi;
    if (a->map.enabled && !sense::ScanMap::keys_reach(a->map, lo, hi)) {
      const double reach = 32768.0 * a->map.resolution;
      throw InvalidParameter(name + ".map.resolution", fmt::format("{}", a->map.resolution),
                             fmt::format("OctoMap's 16-bit keys reach {:.0f} m from the origin at this resolution, and the "
                                         "arena spans [{:.1f}, {:.1f}] x [{:.1f}, {:.1f}] x [{:.1f}, {:.1f}] m: move the arena "
                                         "nearer the origin or choose a coarser resolution",
                                         reach, lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z()));
    }
    const long long cells = a->map.enabled ? sense::ScanMap::cells(a->map, lo, hi) : 0;
    if (cells > sense::kMaxMapCells) {
      throw InvalidParameter(name + ".map.resolution", fmt::format("{}", a->map.resolution),
                             fmt::format("gives this arena's map {} cells, more than 2^36: choose a coarser one", cells));
    }
  }
  if (!carrying.empty()) {
    auto s = std::make_shared<Sensing>(*arena_);
    for (const auto& [name, a] : carrying) {
      Sensing::Carried c{a, sense::make_sensors(a->sensors), {}};
      for (const auto& sensor : c.owned) {
        c.sensors.push_back(sensor.get());
        sight_ = sight_ || sensor->detection() != nullptr;
      }
      s->carried.push_back(std::move(c));
    }
    sensing_ = std::move(s);
  }
  if (arena_->map().scenarios.empty()) return;
  world::CollisionWorld world(arena_);
  std::vector<Vec3> positions;
  for (const world::Scenario& s : arena_->map().scenarios) {
    check_counts(s);
    start_positions(*arena_, *config_, s, positions);
    while (world.agent_count() < s.agents()) world.add_agent(1.0);
    const int p = static_cast<int>(s.pursuers.size());
    for (int i = 0; i < s.agents(); ++i) {
      world.set_agent_radius(i, config_->agent_at(i, p).radius);
      world.place_agent(i, positions[std::size_t(i)]);
    }
    check_start(*arena_, *config_, movers_.get(), world, s, positions);
  }
}

void Sim::check_scenario(const world::Scenario& s) const {
  check_counts(s);
  world::CollisionWorld world(arena_);
  std::vector<Vec3> positions;
  start_positions(*arena_, *config_, s, positions);
  const int p = static_cast<int>(s.pursuers.size());
  for (int i = 0; i < s.agents(); ++i) {
    world.add_agent(config_->agent_at(i, p).radius);
    world.place_agent(i, positions[std::size_t(i)]);
  }
  check_start(*arena_, *config_, movers_.get(), world, s, positions);
}

std::span<const sense::Sensor* const> Sim::sensors(Role role, int rank) const {
  if (!sensing_) return {};
  const AgentConfig* a = &config_->agent(role, rank);
  for (const Sensing::Carried& c : sensing_->carried) {
    if (c.config == a) return c.sensors;
  }
  return {};
}

const sense::Sensor* Sim::sensor(Role role, int rank, std::string_view name) const {
  for (const sense::Sensor* s : sensors(role, rank)) {
    if (s->name() == name) return s;
  }
  return nullptr;
}

SimState::SimState(const Sim& sim) : collider(sim.arena_ptr()) {}

sense::WorldAtInstant world_now(const Sim& sim, const SimState& st) {
  sense::WorldAtInstant w;
  w.scene = sim.ray_scene();
  w.movers = sim.movers();
  w.time = st.time;
  w.push = st.push.get();
  w.map = &sim.arena().map();
  return w;
}

KinematicState SimState::known_state(int i, int j) const {
  const AgentState& o = agents[std::size_t(j)];
  if (!sight_limited(i)) return o.kinematics;
  const Sight::Sighting& m = sight.memory[std::size_t(i * agent_count() + j)];
  if (sensing.detection[std::size_t(i)]->estimate == sense::SightEstimate::kLastSeen || m.time == time) return m.state;
  // Dead reckoning: on at the velocity it had, within the arena (which the agent knows).
  KinematicState k = m.state;
  k.position = o.bounds.clamp(m.state.position + (time - m.time) * m.velocity);
  return k;
}

std::span<const sense::Reading> SimState::readings(int i) const {
  if (sensing.first.empty()) return {};
  const auto b = std::size_t(sensing.first[std::size_t(i)]), e = std::size_t(sensing.first[std::size_t(i) + 1]);
  return std::span<const sense::Reading>(sensing.readings).subspan(b, e - b);
}

const sense::Reading* SimState::reading(int i, std::string_view name) const {
  for (const sense::Reading& r : readings(i)) {
    if (r.sensor->name() == name) return &r;
  }
  return nullptr;
}

}  // namespace peg3d::game
