#pragma once
// A map as plain data: the arena box, its obstacles, terrain meshes and agent starts, in metres. load_map()
// (map_loader.hpp) reads the YAML format documented in docs/maps.md; nothing here exposes yaml-cpp.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <memory>

#include "core/error.hpp"
#include "geometry/angles.hpp"
#include "geometry/pose.hpp"
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

/// A scripted route: the mover's centre runs along the waypoints at a constant speed, starting at the first.
struct PathMotion {
  std::vector<Vec3> waypoints;  ///< m, at least 2, consecutive ones distinct
  double speed = 1.0;           ///< m/s, > 0
  bool loop = true;             ///< after the last waypoint: back to the first (loop) or back the same way
};

/// A scripted circle: the centre turns about `axis` through `center` at constant speed.
struct OrbitMotion {
  Vec3 center = Vec3::Zero();  ///< m
  double radius = 1.0;         ///< m, > 0
  double period = 10.0;        ///< s, one turn, > 0 (counter-clockwise seen from the tip of `axis`)
  Vec3 axis = Vec3::UnitZ();   ///< unit
  double phase = 0.0;          ///< rad at t = 0, measured from +x projected on the orbit's plane (+y if the axis is x)
};

/// A body Bullet moves: it falls, bounces, rolls and is pushed by scripted movers.
struct DynamicMotion {
  double mass = 1.0;                      ///< kg, > 0 (a solid body of uniform density)
  Vec3 velocity = Vec3::Zero();           ///< m/s at t = 0
  Vec3 angular_velocity = Vec3::Zero();   ///< rad/s at t = 0, world frame
  double friction = 0.5;                  ///< Coulomb friction coefficient, >= 0
  double rolling_friction = 0.0;          ///< >= 0 (0: rolls without losing energy)
  double restitution = 0.0;               ///< bounce, in [0, 1]
  /// What an agent's touch means (push mode, game::MoverDynamics::kPush; docs/maps.md): solid, a collision of the
  /// agent, which it does not move; pushable, an event of the log that is no collision, and the agent pushes
  /// the body as Bullet resolves the contact. In the shared mode every body is solid.
  enum class Touch { kSolid, kPushable };
  Touch touch = Touch::kSolid;
};

/// A moving obstacle: a sphere, upright cylinder or box that follows a path or an orbit exactly (kinematic:
/// it pushes dynamic bodies and nothing pushes it) or is a dynamic body of the physics.
struct MoverSpec {
  enum class Motion { kPath, kOrbit, kDynamic };
  Shape shape;
  Motion motion = Motion::kPath;
  PathMotion path;
  OrbitMotion orbit;
  DynamicMotion dynamic;
  Vec3 start = Vec3::Zero();          ///< m, where a dynamic body starts (paths start at their first waypoint)
  Vec3 rotation_deg = Vec3::Zero();   ///< orientation (kept by paths and orbits; the start of dynamic bodies)
  int line = 0;                       ///< line of the entry in the map file (0: unknown)

  bool kinematic() const { return motion != Motion::kDynamic; }
};

/// How moving obstacles are simulated.
struct PhysicsSpec {
  Vec3 gravity = Vec3(0, 0, -9.81);  ///< m/s^2
  int rate_hz = 240;                 ///< physics substeps per second; the game step must be a whole number of them
  /// Poses of the dynamic bodies kept per second for the game (world/bodies/mover_timeline.hpp), between which their
  /// motion is interpolated; 0: every substep (rate_hz, the exact simulated motion). rate_hz must be a whole
  /// multiple of it. Unset (the default): the timeline picks the highest rate dividing rate_hz, down to
  /// MoverTimeline::kMinChosenKeyframeHz, whose worst case fits its budget (every substep whenever that fits).
  std::optional<int> keyframe_hz;
  bool faces_are_physical = true;    ///< the arena's six faces are static planes for dynamic bodies
  int line = 0;                      ///< line of `physics` in the map file (0: unknown)
};

const char* to_string(MoverSpec::Motion m);

/// Where an agent starts; the heading is optional (the game chooses one when absent).
struct AgentStart {
  Vec3 position = Vec3::Zero();  ///< m, strictly inside the arena (the game checks its radius against obstacles)
  std::optional<Heading> heading;
  std::string field;             ///< where it is written, e.g. "scenarios[1].pursuers[0].position", for messages
  int line = 0;                  ///< line of the position in the map file (0: unknown), for messages
};

/// Most agents of one role in a scenario.
inline constexpr int kMaxAgentsPerRole = 256;
/// Most static obstacles (spheres and cylinders, listed and generated) in a map: what every run's collision world
/// holds, per thread. Bounds what a small map file can make a program build before it refuses the file.
inline constexpr int kMaxObstacles = 10000;
/// Most moving obstacles in a map (their motion is bounded separately: world/bodies/mover_timeline.hpp).
inline constexpr int kMaxMovers = 5000;

/// One named set of starts: one or more pursuers and one or more evaders (the paper plays one of each).
struct Scenario {
  std::string name;  ///< unique in its map; letters, digits, '-', '_' and '.', not starting with '.' (it names result files)
  std::vector<AgentStart> pursuers;
  std::vector<AgentStart> evaders;
  int line = 0;  ///< line of the scenario in the map file (0: unknown)

  int agents() const { return static_cast<int>(pursuers.size() + evaders.size()); }
  /// The i-th agent's start, 0 <= i < agents(): the pursuers first, then the evaders (the game's agent order).
  const AgentStart& start(int i) const {
    const int p = static_cast<int>(pursuers.size());
    return i < p ? pursuers[static_cast<std::size_t>(i)] : evaders[static_cast<std::size_t>(i - p)];
  }
  AgentStart& start(int i) { return const_cast<AgentStart&>(std::as_const(*this).start(i)); }
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
  std::vector<MoverSpec> movers;    ///< moving obstacles (index = obstacle id of kMover contacts)
  PhysicsSpec physics;
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

}  // namespace peg3d::world
