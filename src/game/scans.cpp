#include "game/scans.hpp"

#include "core/step_profile.hpp"

namespace peg3d::game {
namespace {

// Tags the sensor streams among the streams derived from a reset's seed.
constexpr std::uint64_t kSensorStream = 0x6c69646172ull;  // "lidar"

}  // namespace

void prepare_scans(const Sim& sim, SimState& st, std::uint64_t seed) {
  SimState::Scans& s = st.scans;
  if (!sim.has_lidars()) {
    s.first.clear();
    return;
  }
  const auto n = std::size_t(st.agent_count());
  s.first.resize(n + 1);
  s.lidar.resize(n);
  if (s.maps.size() < n) s.maps.resize(n);  // never shrunk: a later scenario with more agents reuses their maps
  s.step.assign(n, -1);
  s.rng.resize(n);
  s.balls.resize(n);
  int total = 0, most = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const AgentState& a = st.agents[i];
    s.lidar[i] = sim.lidar(a.role, a.rank);
    const int rays = s.lidar[i] != nullptr ? s.lidar[i]->rays() : 0;
    s.first[i] = total;
    total += rays;
    most = std::max(most, rays);
    if (rays > 0) s.rng[i].seed(derive_seed(seed, {kSensorStream, i}));
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
      map->reserve(rays, s.lidar[i]->config().range);
    }
  }
  s.first[n] = total;
  s.ranges.assign(std::size_t(total), 0.0);
  s.echo.assign(std::size_t(total), 0);
  s.rays.resize(std::size_t(most));
  s.hits.resize(std::size_t(most));
  s.points.resize(std::size_t(most));
}

void scan(const Sim& sim, SimState& st, int i) {
  const StepProfile::Scope profiled(StepProfile::kSensing);
  SimState::Scans& s = st.scans;
  const sense::Lidar& lidar = *s.lidar[std::size_t(i)];
  const AgentState& a = st.agents[std::size_t(i)];
  const auto rays = std::size_t(lidar.rays());
  const std::span<Ray> ray_span = std::span<Ray>(s.rays).first(rays);
  const std::span<sense::RayHit> hits = std::span<sense::RayHit>(s.hits).first(rays);
  lidar.rays_at(a.kinematics.position, a.kinematics.heading, ray_span);
  sense::WorldAtInstant w = world_now(sim, st);
  if (lidar.config().sees_agents) {
    for (int j = 0; j < st.agent_count(); ++j) {
      const AgentState& b = st.agents[std::size_t(j)];
      s.balls[std::size_t(j)] = {b.kinematics.position, b.active ? b.config->radius : 0.0};
    }
    w.balls = s.balls;
  }
  sense::cast_all(w, ray_span, lidar.config().range, i, hits);
  const auto first = std::size_t(s.first[std::size_t(i)]);
  const std::span<double> ranges = std::span<double>(s.ranges).subspan(first, rays);
  const std::span<std::uint8_t> echo = std::span<std::uint8_t>(s.echo).subspan(first, rays);
  sense::read_out(lidar.config(), hits, s.rng[std::size_t(i)], ranges, echo);
  s.step[std::size_t(i)] = st.step;
  if (sense::ScanMap* map = a.config->map.enabled ? s.maps[std::size_t(i)].get() : nullptr) {
    // The scan as a point cloud: an echo's endpoint, or a point beyond the range that carves free space only;
    // without map.insert_agents, no ray that met an agent.
    const double range = lidar.config().range, beyond = range + 2.0 * map->config().resolution;
    const bool agents = map->config().insert_agents;
    std::size_t n = 0;
    for (std::size_t k = 0; k < rays; ++k) {
      if (!agents && hits[k].target == sense::RayTarget::kBall) continue;
      s.points[n++] = ray_span[k].origin + (echo[k] != 0 ? ranges[k] : beyond) * ray_span[k].direction;
    }
    const StepProfile::Scope integrating(StepProfile::kMapInsert);
    map->insert(a.kinematics.position, std::span<const Vec3>(s.points).first(n), range);
  }
}

void scan_due(const Sim& sim, SimState& st) {
  if (st.scans.first.empty()) return;
  for (int i = 0; i < st.agent_count(); ++i) {
    const sense::Lidar* lidar = st.scans.lidar[std::size_t(i)];
    if (lidar == nullptr || !st.events.agents[std::size_t(i)].acted || st.step % lidar->config().period != 0) continue;
    scan(sim, st, i);
  }
}

}  // namespace peg3d::game
