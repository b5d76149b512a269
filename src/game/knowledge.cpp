#include "game/knowledge.hpp"

#include <array>
#include <cmath>

#include "core/step_profile.hpp"
#include "geometry/angles.hpp"
#include "game/views.hpp"
#include "sense/sensor.hpp"

namespace peg3d::game {
namespace {

SimState::Sight::Sighting sighting_of(const AgentState& o, double time) {
  return {o.kinematics, o.config->speed * direction(o.kinematics.heading), time};
}

class WorldProbe final : public SightProbe {
 public:
  WorldProbe(const Sim& sim, const SimState& st, int agent) : sim_(&sim), st_(&st), agent_(agent) {}
  bool mapped(const Vec3& p) const override {
    const sense::ScanMap* map = st_->map(agent_);
    return map != nullptr && !std::isnan(map->log_odds(map->key_of(p)));
  }
  bool clear(const Vec3& a, const Vec3& b) const override {
    const Vec3 d = b - a;
    const double length = d.norm();
    if (!(length > 0.0)) return true;
    const Ray ray{a, d / length};
    sense::RayHit hit;
    sense::cast_all(world_now(*sim_, *st_), {&ray, 1}, length, -1, {&hit, 1});
    return hit.target == sense::RayTarget::kNone;
  }
  double clearance(const Vec3& p) const override { return sense_obstacle(*sim_, *st_, p).distance; }
  const Sim* sim_;
  const SimState* st_;
  int agent_;
};

}  // namespace

void prepare_sight(const Sim& sim, SimState& st) {
  SimState::Sight& s = st.sight;
  if (!sim.limits_sight()) {
    s.memory.clear();
    s.visible.clear();
    return;
  }
  const int n = st.agent_count();
  if (s.probes.size() < std::size_t(n)) s.probes.resize(std::size_t(n));  // never shrunk, like the scans' maps
  for (int i = 0; i < n; ++i) {
    if (!s.probes[std::size_t(i)]) s.probes[std::size_t(i)] = std::make_unique<WorldProbe>(sim, st, i);
    auto& probe = static_cast<WorldProbe&>(*s.probes[std::size_t(i)]);
    probe.sim_ = &sim, probe.st_ = &st;  // the Sim this reset plays, and the state where it lives now
  }
  s.memory.resize(std::size_t(n * n));
  s.visible.assign(std::size_t(n * n), 0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) s.memory[std::size_t(i * n + j)] = sighting_of(st.agents[std::size_t(j)], 0.0);
  }
}

void look(const Sim& sim, SimState& st) {
  (void)sim;
  SimState::Sight& s = st.sight;
  if (s.memory.empty()) return;
  const int n = st.agent_count();
  for (int i = 0; i < n; ++i) {
    const AgentState& a = st.agents[std::size_t(i)];
    // Its detector's latest reading: per agent, 1 when it saw that one (game/sensing.hpp read it this step, as every
    // agent in the game reads every step; one out of the game sees nothing).
    const sense::Reading* seen = nullptr;
    if (st.sight_limited(i)) {
      for (const sense::Reading& r : st.readings(i)) {
        if (r.sensor->detection() != nullptr) seen = &r;
      }
    }
    const bool limited = seen != nullptr && a.active;
    const auto [lo, hi] = st.of_role(opposing(a.role));
    for (int j = lo; j < hi; ++j) {
      const AgentState& o = st.agents[std::size_t(j)];
      const auto k = std::size_t(i * n + j);
      s.visible[k] = limited && o.active && seen->echo[std::size_t(j)] != 0;
      if (s.visible[k]) s.memory[k] = sighting_of(o, st.time);
    }
  }
  // Pooling, per team: for each opponent, the newest sighting among the sharers (the lower index among equally
  // new ones), then given to all of them: read before written, so the order of the agents does not matter.
  const auto shares = [&](int m) {
    const sense::Detection* d = st.sensing.detection[std::size_t(m)];
    return d != nullptr && d->share;
  };
  const int p = st.pursuers;
  for (const auto& [team_lo, team_hi, lo, hi] : {std::array{0, p, p, n}, std::array{p, n, 0, p}}) {
    int first = team_lo;
    while (first < team_hi && !shares(first)) ++first;
    if (first == team_hi) continue;
    for (int j = lo; j < hi; ++j) {
      int best = first;
      bool seen = false;
      for (int m = first; m < team_hi; ++m) {
        if (!shares(m)) continue;
        const auto k = std::size_t(m * n + j);
        seen = seen || s.visible[k] != 0;
        if (s.memory[k].time > s.memory[std::size_t(best * n + j)].time) best = m;
      }
      const SimState::Sight::Sighting newest = s.memory[std::size_t(best * n + j)];
      for (int m = first; m < team_hi; ++m) {
        if (!shares(m)) continue;
        s.memory[std::size_t(m * n + j)] = newest;
        s.visible[std::size_t(m * n + j)] = seen;
      }
    }
  }
}

}  // namespace peg3d::game
