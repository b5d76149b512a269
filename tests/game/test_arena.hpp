#pragma once
// Small arenas built in code for game tests (no files, no cache).

#include <memory>
#include <vector>

#include "world/arena.hpp"

namespace peg3d::testing {

inline world::Scenario scenario(const char* name, const Vec3& pursuer, const Vec3& evader) {
  world::Scenario s;
  s.name = name;
  s.pursuer.position = pursuer;
  s.evader.position = evader;
  return s;
}

/// An arena of the given size with the given spheres; boundary faces are not in the distance field.
inline std::shared_ptr<const world::Arena> make_arena(const Vec3& size, std::vector<world::SphereObstacle> spheres,
                                                      std::vector<world::Scenario> scenarios, double resolution = 0.25) {
  world::MapSpec m;
  m.name = "test";
  m.bounds = {Vec3::Zero(), size};
  m.resolution = resolution;
  m.max_distance = 5.0;
  m.floor_is_obstacle = m.ceiling_is_obstacle = m.walls_is_obstacle = false;
  m.spheres = std::move(spheres);
  m.scenarios = std::move(scenarios);
  return world::Arena::build(m);
}

}  // namespace peg3d::testing
