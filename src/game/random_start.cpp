#include "game/random_start.hpp"

#include <algorithm>
#include <vector>

#include "core/random.hpp"

namespace peg3d::game {

world::Scenario random_start(const Sim& sim, const world::Scenario& like, std::uint64_t seed, double gap_setting) {
  constexpr int kDraws = 1000;
  const GameConfig& g = sim.config();
  const world::Arena& arena = sim.arena();
  const double gap = std::max(gap_setting, g.capture_distance);
  const int n = like.agents(), p = static_cast<int>(like.pursuers.size());
  const auto radius = [&](int i) { return g.agent_at(i, p).radius; };
  Rng rng(seed);
  std::vector<Vec3> placed;
  placed.reserve(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const double keep = radius(i) + kRandomStartClearance;
    const Box box = arena.bounds().shrunk(keep);
    if ((box.hi.array() < box.lo.array()).any()) return like;
    // Clear of the map, and of the agents placed so far: their radii apart within a role, the gap across.
    const auto fits = [&](const Vec3& x) {
      if (arena.nearest_shape(x).distance < keep || arena.below_solid_terrain(x)) return false;
      if (const world::MoverTimeline* movers = sim.movers(); movers != nullptr && movers->nearest_at_start(x, keep).mover >= 0)
        return false;
      for (int j = 0; j < i; ++j) {
        const double d = (x - placed[std::size_t(j)]).norm();
        if ((j < p) == (i < p) ? d < keep + radius(j) : d <= gap) return false;
      }
      return true;
    };
    for (int d = 0; d < kDraws && placed.size() == std::size_t(i); ++d) {
      const Vec3 x(uniform(rng, box.lo.x(), box.hi.x()), uniform(rng, box.lo.y(), box.hi.y()),
                   uniform(rng, box.lo.z(), box.hi.z()));
      if (fits(x)) placed.push_back(x);
    }
    if (placed.size() == std::size_t(i)) return like;
  }
  world::Scenario s;
  s.name = like.name;
  s.line = like.line;
  s.pursuers.resize(like.pursuers.size());
  s.evaders.resize(like.evaders.size());
  for (int i = 0; i < n; ++i) s.start(i).position = placed[std::size_t(i)];
  return s;
}

}  // namespace peg3d::game
