#pragma once
// A map as plain data: the arena box, its obstacles, terrain meshes and agent starts, in metres. load_map()
// reads the YAML format documented in docs/maps.md; nothing here exposes yaml-cpp.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <memory>

#include "core/error.hpp"
#include "geometry/angles.hpp"
#include "geometry/vector.hpp"

namespace peg3d::world {

struct TriangleMesh;

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
  /// The placed triangles when load_map() has imported the file already (Arena::build() then does not read
  /// it again); null for entries written in code.
  std::shared_ptr<const TriangleMesh> imported;
};

/// Where an agent starts; the heading is optional (the game chooses one when absent).
struct AgentStart {
  Vec3 position = Vec3::Zero();  ///< m, strictly inside the arena (the game checks its radius against obstacles)
  std::optional<Heading> heading;
  std::string field;             ///< where it is written, e.g. "scenarios[1].pursuers[0].position", for messages
  int line = 0;                  ///< line of the position in the map file (0: unknown), for messages
};

/// Most agents of one role in a scenario.
inline constexpr int kMaxAgentsPerRole = 256;

/// One named set of starts: one or more pursuers and one or more evaders (the paper plays one of each).
struct Scenario {
  std::string name;  ///< unique in its map; letters, digits, '-', '_' and '.', not starting with '.' (it names result files)
  std::vector<AgentStart> pursuers;
  std::vector<AgentStart> evaders;
  int line = 0;  ///< line of the scenario in the map file (0: unknown)

  int agents() const { return static_cast<int>(pursuers.size() + evaders.size()); }
};

/// Whether `name` may name a scenario (and so a result file): 1 to 64 characters from [A-Za-z0-9._-], not
/// starting with '.', so it can never climb out of an output folder or hide a file.
bool is_safe_name(std::string_view name);

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

/// A bad map. what() is "FILE:LINE: FIELD: message" ("FILE: message" when there is no line); field() is
/// empty for syntax errors.
class MapError : public InputError {
 public:
  using InputError::InputError;
};

/// Reads and validates a YAML map (docs/maps.md): every problem throws MapError naming file, line and
/// field. Terrain meshes are imported to check them (missing, empty, malformed, no triangles, non-finite).
MapSpec load_map(const std::filesystem::path& file);

}  // namespace peg3d::world
