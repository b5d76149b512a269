#include "game/sensing.hpp"

#include "core/step_profile.hpp"

namespace peg3d::game {

void prepare_sensing(const Sim& sim, SimState& st, std::uint64_t seed) {
  SimState::Sensing& s = st.sensing;
  if (!sim.senses()) {
    s.first.clear();
    s.detection.clear();
    return;
  }
  const auto n = std::size_t(st.agent_count());
  s.first.resize(n + 1);
  if (s.maps.size() < n) s.maps.resize(n);  // never shrunk: a later scenario with more agents reuses their maps
  s.map_step.assign(n, -1);
  s.detection.assign(n, nullptr);
  s.balls.resize(n);
  s.targets.resize(n);
  // The slots: each agent's sensors in order, each given a scratch of its sensor's that no other slot has now.
  ++s.resets;
  const auto scratch_for = [&s](const sense::Sensor* sensor) {
    for (SimState::Sensing::Scratch& c : s.scratch) {
      if (c.sensor == sensor && c.used != s.resets) {
        c.used = s.resets;
        return c.scratch.get();
      }
    }
    s.scratch.push_back({sensor, s.resets, sensor->make_scratch()});
    return s.scratch.back().scratch.get();
  };
  std::size_t slot = 0;
  int values = 0, points = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const AgentState& a = st.agents[i];
    s.first[i] = int(slot);
    for (const sense::Sensor* sensor : sim.sensors(a.role, a.rank)) {
      if (s.slots.size() <= slot) s.slots.resize(slot + 1);
      SimState::Sensing::Slot& sl = s.slots[slot++];
      sl.sensor = sensor;
      sl.scratch = scratch_for(sensor);
      sl.begin = values;
      sl.size = sensor->values(int(n));
      values += sl.size;
      if (sensor->stream() != 0) sl.rng.seed(derive_seed(seed, {sensor->stream(), i}));
      if (sensor->detection() != nullptr) s.detection[i] = sensor->detection();
      if (sensor->map_range() > 0.0) points = std::max(points, sensor->map_points_max());
    }
    // Agent i's map: made when first needed (or when its settings change), else cleared unless it persists; a
    // map an agent does not use now is kept for a later scenario that gives it one again.
    const sense::ScanMapConfig& mc = a.config->map;
    std::unique_ptr<sense::ScanMap>& map = s.maps[i];
    if (mc.enabled) {
      if (!map || map->config() != mc) {
        map = std::make_unique<sense::ScanMap>(mc, sim.arena().bounds().lo, sim.arena().bounds().hi);
      } else if (!mc.persist) {
        map->clear();
      }
      for (const sense::Sensor* sensor : sim.sensors(a.role, a.rank)) {
        if (sensor->map_range() > 0.0) map->reserve(sensor->map_points_max(), sensor->map_range());
      }
    }
  }
  s.first[n] = int(slot);
  s.values.assign(std::size_t(values), 0.0);
  s.echo.assign(std::size_t(values), 0);
  s.readings.resize(slot);
  for (std::size_t k = 0; k < slot; ++k) {
    const SimState::Sensing::Slot& sl = s.slots[k];
    s.readings[k] = {std::span<const double>(s.values).subspan(std::size_t(sl.begin), std::size_t(sl.size)),
                     std::span<const std::uint8_t>(s.echo).subspan(std::size_t(sl.begin), std::size_t(sl.size)), -1,
                     sl.sensor};
  }
  s.points.resize(std::size_t(points));
}

void scan(const Sim& sim, SimState& st, int i, int k) {
  const StepProfile::Scope profiled(StepProfile::kSensing);
  SimState::Sensing& s = st.sensing;
  const auto slot = std::size_t(s.first[std::size_t(i)] + k);
  SimState::Sensing::Slot& sl = s.slots[slot];
  const sense::Sensor& sensor = *sl.sensor;
  const AgentState& a = st.agents[std::size_t(i)];
  // The world now, every agent in it (its sphere; none out of the game), and which of them are its opponents.
  for (int j = 0; j < st.agent_count(); ++j) {
    const AgentState& b = st.agents[std::size_t(j)];
    s.balls[std::size_t(j)] = {b.kinematics.position, b.active ? b.config->radius : 0.0};
    s.targets[std::size_t(j)] = b.active && b.role != a.role;
  }
  sense::ScanContext context;
  context.world = world_now(sim, st);
  context.world.balls = s.balls;
  context.eye = a.kinematics.position;
  context.heading = a.kinematics.heading;
  context.self = i;
  context.targets = s.targets;
  const auto b = std::size_t(sl.begin), n = std::size_t(sl.size);
  sensor.scan(context, sl.rng, {std::span<double>(s.values).subspan(b, n), std::span<std::uint8_t>(s.echo).subspan(b, n)},
              sl.scratch);
  sense::Reading& r = s.readings[slot];
  r.step = st.step;
  sense::ScanMap* map = a.config->map.enabled ? s.maps[std::size_t(i)].get() : nullptr;
  if (map == nullptr || sensor.map_range() <= 0.0) return;
  // The scan as a point cloud: an echo's endpoint, or a point beyond the range that carves free space only;
  // without map.insert_agents, no ray that met an agent.
  const double range = sensor.map_range(), beyond = range + 2.0 * map->config().resolution;
  const std::size_t points = sensor.map_points(r, sl.scratch, !map->config().insert_agents, beyond, s.points);
  const StepProfile::Scope integrating(StepProfile::kMapInsert);
  map->insert(a.kinematics.position, std::span<const Vec3>(s.points).first(points), range);
  s.map_step[std::size_t(i)] = st.step;
}

void scan_all(const Sim& sim, SimState& st, int i) {
  if (st.sensing.first.empty()) return;
  const int n = st.sensing.first[std::size_t(i) + 1] - st.sensing.first[std::size_t(i)];
  for (int k = 0; k < n; ++k) scan(sim, st, i, k);
}

void scan_due(const Sim& sim, SimState& st) {
  SimState::Sensing& s = st.sensing;
  if (s.first.empty()) return;
  for (int i = 0; i < st.agent_count(); ++i) {
    if (!st.events.agents[std::size_t(i)].acted) continue;
    const int first = s.first[std::size_t(i)], n = s.first[std::size_t(i) + 1] - first;
    for (int k = 0; k < n; ++k) {
      if (st.step % s.slots[std::size_t(first + k)].sensor->period() == 0) scan(sim, st, i, k);
    }
  }
}

}  // namespace peg3d::game
