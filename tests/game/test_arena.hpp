#pragma once
// Small arenas built in code for game tests (no files, no cache).

#include <memory>
#include <vector>

#include "game/episode.hpp"
#include "players/lineup.hpp"
#include "world/arena.hpp"
#include "world/world_test_support.hpp"

namespace peg3d::testing {

inline world::Scenario scenario(const char* name, const Vec3& pursuer, const Vec3& evader) {
  world::Scenario s;
  s.name = name;
  s.pursuers.push_back({pursuer, std::nullopt, "", 0});
  s.evaders.push_back({evader, std::nullopt, "", 0});
  return s;
}

/// A scenario of several pursuers and evaders.
inline world::Scenario team(const char* name, const std::vector<Vec3>& pursuers, const std::vector<Vec3>& evaders) {
  world::Scenario s;
  s.name = name;
  for (const Vec3& p : pursuers) s.pursuers.push_back({p, std::nullopt, "", 0});
  for (const Vec3& e : evaders) s.evaders.push_back({e, std::nullopt, "", 0});
  return s;
}

/// An arena of the given size with the given spheres; boundary faces are not in the distance field.
inline std::shared_ptr<const world::Arena> make_arena(const Vec3& size, std::vector<world::SphereObstacle> spheres,
                                                      std::vector<world::Scenario> scenarios, double resolution = 0.25) {
  world::MapSpec m = world::testing::empty_spec(size, resolution, 5.0);
  m.name = "test";
  m.spheres = std::move(spheres);
  m.scenarios = std::move(scenarios);
  return world::Arena::build(m);
}

/// A 30 x 30 x 10 m room with (or without) a full-height pillar of radius 3 m at its centre, for the partial game's
/// tests: an agent at y = 15 on one side cannot see one on the other.
inline std::shared_ptr<const world::Arena> pillar_room(bool pillar = true) {
  world::MapSpec m = world::testing::empty_spec({30, 30, 10}, 0.25, 5.0);
  m.name = "pillar";
  if (pillar) m.cylinders.push_back({{15, 15, 0}, 3.0, 10.0});
  return world::Arena::build(m);
}

/// The configuration's policies for every agent of `scenario` (pursuers seeded from 1, evaders from 2).
inline players::Lineup lineup_for(const game::GameConfig& c, const world::Scenario& s, std::uint64_t pursuer_seed = 1,
                               std::uint64_t evader_seed = 2) {
  players::Lineup l;
  players::add_configured(l, c, game::Role::kPursuer, static_cast<int>(s.pursuers.size()), pursuer_seed);
  players::add_configured(l, c, game::Role::kEvader, static_cast<int>(s.evaders.size()), evader_seed);
  return l;
}

/// One episode of `scenario` on a fresh state, played by the configuration's policies.
inline game::EpisodeResult play_once(const game::Sim& sim, const world::Scenario& s, std::uint64_t seed,
                                     game::Trace* trace = nullptr) {
  game::SimState state(sim);
  players::Lineup l = lineup_for(sim.config(), s);
  if (trace) trace->reserve(sim.max_steps(), s.agents());
  return game::play(sim, state, s, l.policies(), false, seed, trace);
}

}  // namespace peg3d::testing
