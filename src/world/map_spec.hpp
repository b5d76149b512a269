#pragma once
// A map as plain data: the arena box, its obstacles, terrain meshes and agent starts, in metres. load_map()
// reads the YAML format documented in docs/maps.md; nothing here exposes yaml-cpp.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/angles.hpp"
#include "geometry/vector.hpp"

namespace peg3d::world {

/// A solid ball.
struct SphereObstacle {
  Vec3 center = Vec3::Zero();  ///< m
  double radius = 1.0;         ///< m, > 0
};

/// A solid upright cylinder: axis +z from the centre of its base disc.
struct CylinderObstacle {
  Vec3 base = Vec3::Zero();  ///< m, centre of the bottom disc
  double radius = 1.0;       ///< m, > 0
  double height = 1.0;       ///< m, > 0
};

/// A triangle mesh placed in the world: v_world = R * (scale * v_file) + translation, where
/// R = Rz(rotation_deg.z) * Ry(rotation_deg.y) * Rx(rotation_deg.x) (rotations about the fixed world axes,
/// x first).
struct TerrainMesh {
  std::filesystem::path file;                ///< absolute, resolved against the map file's folder
  double scale = 1.0;                        ///< uniform scale, > 0
  Vec3 rotation_deg = Vec3::Zero();          ///< degrees about world x, y, z (applied x, then y, then z)
  Vec3 translation = Vec3::Zero();           ///< m
  bool solid_below = false;                  ///< everything under the surface counts as occupied (height field)
  int line = 0;                              ///< line of the entry in the map file (1-based, 0 unknown), for errors
};

/// Where an agent starts; the heading is optional (the game chooses one when absent).
struct AgentStart {
  Vec3 position = Vec3::Zero();  ///< m, strictly inside the arena and outside every obstacle
  std::optional<Heading> heading;
};

/// One named pair of starts.
struct Scenario {
  std::string name;
  AgentStart pursuer;
  AgentStart evader;
};

/// Everything a map file says. Obstacles from random generators are already expanded, in a stable order
/// (explicit ones first, then each generator's in the file's order).
struct MapSpec {
  std::filesystem::path source;  ///< the map file as given to load_map (empty for maps built in code)
  std::string name;              ///< optional display name
  Box bounds;                    ///< arena box, m
  double resolution = 0.2;       ///< occupancy voxel edge, m, > 0
  double max_distance = 5.0;     ///< distance-field cap, m, >= resolution
  bool floor_is_obstacle = true;    ///< the face z = bounds.lo.z is an obstacle in the octree and distance field
  bool ceiling_is_obstacle = true;  ///< the face z = bounds.hi.z
  bool walls_is_obstacle = true;    ///< the four vertical faces
  std::vector<SphereObstacle> spheres;
  std::vector<CylinderObstacle> cylinders;
  std::vector<TerrainMesh> meshes;
  std::vector<Scenario> scenarios;  ///< at least one; a single `start:` becomes a scenario named "default"

  /// The scenario called `name`, or nullptr.
  const Scenario* find_scenario(const std::string& name) const;
};

/// A bad map. what() is "FILE:LINE: FIELD: message" ("FILE: message" when there is no line).
class MapError : public std::runtime_error {
 public:
  MapError(std::filesystem::path file, int line, std::string field, const std::string& message);
  const std::filesystem::path& file() const noexcept { return file_; }
  /// 1-based line in the map file, 0 when unknown.
  int line() const noexcept { return line_; }
  /// Dotted path of the offending field, e.g. "obstacles[2].radius"; empty for syntax errors.
  const std::string& field() const noexcept { return field_; }

 private:
  std::filesystem::path file_;
  int line_;
  std::string field_;
};

/// Reads and validates a YAML map (docs/maps.md): every problem throws MapError naming file, line and
/// field. Terrain meshes are imported to check them (missing, empty, malformed, no triangles, non-finite).
MapSpec load_map(const std::filesystem::path& file);

}  // namespace peg3d::world
