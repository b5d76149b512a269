#pragma once
// Helpers shared by the world tests: test data paths, scratch folders, small arenas built in code.

#include <filesystem>
#include <memory>
#include <string>

#include "support/scratch_dir.hpp"
#include "world/arena.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::world::testing {

inline std::filesystem::path data_dir() { return PEG3D_TEST_DATA_DIR; }
inline std::filesystem::path mesh_path(const std::string& name) { return data_dir() / "meshes" / name; }
inline std::filesystem::path source_dir() { return PEG3D_SOURCE_DIR; }

using peg3d::testing::ScratchDir;

/// An empty arena box of the given size from the origin, no boundary faces, one scenario.
inline MapSpec empty_spec(const Vec3& size, double resolution, double max_distance = 3.0) {
  MapSpec s;
  s.bounds = Box{Vec3::Zero(), size};
  s.resolution = resolution;
  s.max_distance = max_distance;
  s.floor_is_obstacle = s.ceiling_is_obstacle = s.walls_is_obstacle = false;
  Scenario sc;
  sc.name = "default";
  sc.pursuers.push_back({Vec3::Constant(0.5), std::nullopt, "", 0});
  sc.evaders.push_back({size - Vec3::Constant(0.5), std::nullopt, "", 0});
  s.scenarios.push_back(std::move(sc));
  return s;
}

/// A terrain entry for a test mesh, placed as given.
inline TerrainMesh mesh_entry(const std::string& name, const Vec3& translation = Vec3::Zero(), double scale = 1.0,
                              bool solid_below = false) {
  TerrainMesh m;
  m.file = mesh_path(name);
  m.scale = scale;
  m.translation = translation;
  m.solid_below = solid_below;
  return m;
}

inline std::shared_ptr<const Arena> build(const MapSpec& spec) { return Arena::build(spec, BuildOptions{}); }

}  // namespace peg3d::world::testing
