#include "game/starts.hpp"

#include <array>

#include <fmt/format.h>

#include "core/validation.hpp"
#include "world/map/movers.hpp"

namespace peg3d::game {

void check_counts(const world::Scenario& s) {
  const auto check = [&](std::size_t n, const char* role) {
    if (n < 1 || n > static_cast<std::size_t>(world::kMaxAgentsPerRole)) {
      throw InvalidParameter(fmt::format("scenario '{}' {}s", s.name, role), std::to_string(n),
                             fmt::format("must lie in [1, {}]", world::kMaxAgentsPerRole));
    }
  };
  check(s.pursuers.size(), "pursuer");
  check(s.evaders.size(), "evader");
}

void check_start(const world::Arena& arena, const GameConfig& g, const world::MoverTimeline* movers,
                 const world::CollisionWorld& world, const world::Scenario& s, std::span<const Vec3> positions) {
  const int n = s.agents(), p = static_cast<int>(s.pursuers.size());
  const std::filesystem::path& file = arena.map().source;
  for (int i = 0; i < n; ++i) {
    const Role role = role_at(i, p);
    const world::AgentStart& a = s.start(i);
    const double radius = g.agent_at(i, p).radius;
    if (arena.below_solid_terrain(positions[std::size_t(i)])) {
      throw StartError(file, a.line, a.field.empty() ? "scenario " + s.name : a.field,
                       fmt::format("scenario '{}': the {} starts under solid terrain", s.name, to_string(role)));
    }
    if (const auto c = world.overlap(i)) {
      throw StartError(file, a.line, a.field.empty() ? "scenario " + s.name : a.field,
                       fmt::format("scenario '{}': the {} (radius {} m) starts overlapping {} {} (penetration {:.3f} m)",
                                   s.name, to_string(role), radius, world::to_string(c->kind), c->obstacle_id,
                                   c->penetration));
    }
    if (movers != nullptr) {
      // The movers near the start (a superset of those it overlaps), in index order; all of them when the
      // index cannot say.
      std::array<int, 256> near;
      const Vec3& p = positions[std::size_t(i)];
      int n = movers->candidates({p, p}, radius, 0.0, 0.0, near);
      const bool all = n < 0 || n > static_cast<int>(near.size());
      if (all) n = movers->count();
      const auto check = [&](int m) {
        const double gap = signed_distance(movers->mover(m).shape, movers->pose(m, 0.0), p) - radius;
        if (gap < 0.0) {
          throw StartError(file, a.line, a.field.empty() ? "scenario " + s.name : a.field,
                           fmt::format("scenario '{}': the {} (radius {} m) starts overlapping {} (penetration {:.3f} m)",
                                       s.name, to_string(role), radius,
                                       world::describe_mover(movers->mover(m), m), -gap));
        }
      };
      for (int k = 0; k < n; ++k) check(all ? k : near[std::size_t(k)]);
      // Push mode leaves the dynamic bodies out of the timeline's queries: they are checked at their starts.
      if (!movers->with_dynamic()) {
        for (int m = 0; m < movers->count(); ++m) {
          if (!movers->mover(m).kinematic()) check(m);
        }
      }
    }
    for (int j = 0; j < i; ++j) {
      if (!g.team.collide(role, role_at(j, p))) continue;
      const double reach = radius + g.agent_at(j, p).radius;
      if ((positions[std::size_t(i)] - positions[std::size_t(j)]).norm() <= reach) {
        throw StartError(file, a.line, a.field.empty() ? "scenario " + s.name : a.field,
                         fmt::format("scenario '{}': the {} starts overlapping agent {} (agents collide: {})", s.name,
                                     to_string(role), j, config::enum_name(kAgentCollisionNames, g.team.agent_collisions)));
      }
    }
  }
}

void start_positions(const world::Arena& arena, const GameConfig& g, const world::Scenario& s, std::vector<Vec3>& out) {
  const int n = s.agents(), p = static_cast<int>(s.pursuers.size());
  out.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double radius = g.agent_at(i, p).radius;
    out[std::size_t(i)] = arena.bounds().shrunk(radius).clamp(s.start(i).position);
  }
}

}  // namespace peg3d::game
