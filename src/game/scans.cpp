#include "game/scans.hpp"

#include "core/step_profile.hpp"

namespace peg3d::game {
namespace {

// Tags the sensor streams among the streams derived from a reset's seed.
constexpr std::uint64_t kSensorStream = 0x6c69646172ull;  // "lidar"

}  // namespace

void prepare_scans(const Sim& sim, SimState& st, std::uint64_t seed) {
  SimState::Scans& s = st.scans;
  if (sim.ray_scene() == nullptr) {
    s.first.clear();
    return;
  }
  const auto n = std::size_t(st.agent_count());
  s.first.resize(n + 1);
  s.lidar.resize(n);
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
  }
  s.first[n] = total;
  s.ranges.assign(std::size_t(total), 0.0);
  s.echo.assign(std::size_t(total), 0);
  s.rays.resize(std::size_t(most));
  s.hits.resize(std::size_t(most));
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
  sense::WorldAtInstant w;
  w.scene = sim.ray_scene();
  w.movers = sim.movers();
  w.time = st.time;
  w.push = st.push.get();
  w.map = &sim.arena().map();
  if (lidar.config().sees_agents) {
    for (int j = 0; j < st.agent_count(); ++j) {
      const AgentState& b = st.agents[std::size_t(j)];
      s.balls[std::size_t(j)] = {b.kinematics.position, b.active ? b.config->radius : 0.0};
    }
    w.balls = s.balls;
  }
  sense::cast_all(w, ray_span, lidar.config().range, i, hits);
  const auto first = std::size_t(s.first[std::size_t(i)]);
  sense::read_out(lidar.config(), hits, s.rng[std::size_t(i)], std::span<double>(s.ranges).subspan(first, rays),
                  std::span<std::uint8_t>(s.echo).subspan(first, rays));
  s.step[std::size_t(i)] = st.step;
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
