#include "game/random_start.hpp"

#include <algorithm>
#include <vector>

#include "core/random.hpp"

namespace peg3d::game {

world::Scenario random_start(const Sim& sim, const world::Scenario& like, std::uint64_t seed) {
  constexpr int kDraws = 1000;
  const GameConfig& g = sim.config();
  const world::Arena& arena = sim.arena();
  const double gap = std::max(g.training.random_start_gap, g.capture_distance);
  const int n = like.agents(), p = static_cast<int>(like.pursuers.size());
  Rng rng(seed);
  const auto unit = [&rng] { return unit_uniform(rng); };
  std::vector<Vec3> placed;
  std::vector<double> radii;
  placed.reserve(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const bool pursuer = i < p;
    const double radius = g.agent(pursuer ? Role::kPursuer : Role::kEvader, pursuer ? i : i - p).radius;
    const double keep = radius + kRandomStartClearance;
    const Box box = arena.bounds().shrunk(keep);
    bool found = false;
    if ((box.hi.array() < box.lo.array()).any()) return like;
    for (int d = 0; d < kDraws && !found; ++d) {
      const Vec3 x(box.lo.x() + unit() * (box.hi.x() - box.lo.x()), box.lo.y() + unit() * (box.hi.y() - box.lo.y()),
                   box.lo.z() + unit() * (box.hi.z() - box.lo.z()));
      if (arena.nearest_shape(x).distance < keep || arena.below_solid_terrain(x)) continue;
      if (const world::MoverTimeline* movers = sim.movers(); movers != nullptr && movers->nearest(x, 0.0, keep).mover >= 0)
        continue;
      found = true;
      for (int j = 0; j < i && found; ++j) {
        const bool same_role = (j < p) == pursuer;
        const double least = same_role ? radius + radii[std::size_t(j)] + kRandomStartClearance : gap;
        found = same_role ? (x - placed[std::size_t(j)]).norm() >= least : (x - placed[std::size_t(j)]).norm() > least;
      }
      if (found) {
        placed.push_back(x);
        radii.push_back(radius);
      }
    }
    if (!found) return like;
  }
  world::Scenario s;
  s.name = like.name;
  s.line = like.line;
  s.pursuers.resize(like.pursuers.size());
  s.evaders.resize(like.evaders.size());
  for (int i = 0; i < n; ++i) (i < p ? s.pursuers[std::size_t(i)] : s.evaders[std::size_t(i - p)]).position = placed[std::size_t(i)];
  return s;
}

}  // namespace peg3d::game
