#pragma once
// The arena: the fixed, read-only model of a map shared by every episode and thread (like MuJoCo's mjModel).
// It holds the map, the imported terrain triangles, the OctoMap octree (serialized) and the distance field.
// Built once per map; a second build of the same map is read from an on-disk cache.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "geometry/vector.hpp"
#include "world/bodies/contact.hpp"
#include "world/field/distance_field.hpp"
#include "world/map/map_spec.hpp"
#include "world/map/obstacle_geometry.hpp"
#include "world/map/triangle_mesh.hpp"

namespace peg3d::world {

struct TerrainShapes;
struct StaticPhysicsShapes;

class MoverTimeline;

// ObstacleKind (world/bodies/contact.hpp): kBoundary is a face of the arena box (octree and distance field only, never
// a collision: the game keeps agents inside the box); kAgent is another agent (when the game lets agents
// collide); kMover is a moving obstacle (MapSpec::movers, by index).

/// Figures about a built arena.
struct ArenaStats {
  std::size_t spheres = 0;            ///< sphere obstacles
  std::size_t cylinders = 0;          ///< cylinder obstacles
  std::size_t meshes = 0;             ///< terrain meshes
  std::size_t triangles = 0;          ///< triangles over all meshes
  double resolution = 0.0;            ///< m, effective voxel edge
  std::size_t occupied_voxels = 0;    ///< voxels (at the resolution) marked occupied in the octree
  std::array<int, 3> field_dims{};    ///< distance-field cells on x, y, z (the arena plus one cell each side)
  std::size_t field_cells = 0;        ///< product of field_dims
  std::size_t field_bytes = 0;        ///< memory the Arena keeps for the distance field
  std::size_t octree_bytes = 0;       ///< size of the serialized octree (.bt)
  std::size_t build_peak_bytes = 0;   ///< estimated transient memory of building the field (0 on a cache hit)
  double voxelize_seconds = 0.0;      ///< occupancy from the shapes
  double octree_seconds = 0.0;        ///< filling and pruning the OcTree
  double edt_seconds = 0.0;           ///< DynamicEDTOctomap and the copy into the compact field
  double build_seconds = 0.0;         ///< whole Arena::build wall time, mesh import and cache included
  bool loaded_from_cache = false;
  std::uint64_t cache_key = 0;        ///< content hash keying the cache file
  std::filesystem::path cache_file;   ///< empty when caching is off
  std::string cache_status;           ///< "off", "hit", "stored", "<why the file was unusable>; stored", "not stored (<error>)"
};

/// How to build an arena.
struct BuildOptions {
  std::optional<double> resolution_override;         ///< m, replaces the map's resolution; > 0
  std::optional<std::filesystem::path> cache_dir;    ///< where built worlds are cached; nullopt: no cache
  std::size_t max_field_bytes = std::size_t{4} << 30;  ///< refuse builds whose estimated peak memory is larger
};

class Arena {
 public:
  /// Imports the meshes, voxelizes every obstacle conservatively into an OctoMap OcTree and computes the
  /// distance field with dynamicEDT3D, or loads both from the cache. Throws MapError for bad input (mesh
  /// files, a resolution that is too fine or needs more than max_field_bytes).
  static std::shared_ptr<const Arena> build(const MapSpec& spec, const BuildOptions& options = {});

  const MapSpec& map() const { return spec_; }
  const Box& bounds() const { return spec_.bounds; }
  const ArenaStats& stats() const { return stats_; }
  double max_distance() const { return spec_.max_distance; }
  double resolution() const { return stats_.resolution; }
  /// Terrain meshes in world coordinates, in map order (index = obstacle id of kMesh contacts).
  const std::vector<TriangleMesh>& meshes() const { return meshes_; }
  const DistanceField& distance_field() const { return field_; }

  /// Distance (m, capped at max_distance) from p to the nearest obstacle and the obstacle's point nearest to p:
  /// for spheres, cylinders and meshes the nearest occupied voxel (within a voxel diagonal of exact), for the
  /// arena faces that count as obstacles the face itself (exact). Thread-safe, no allocation, no locking.
  NearestObstacle nearest_obstacle(const Vec3& p) const { return field_.nearest(p); }

  /// nearest_obstacle() ignoring the arena faces, whatever the map says: spheres, cylinders and meshes only
  /// (for callers that handle the box themselves). Same guarantees.
  NearestObstacle nearest_shape(const Vec3& p) const { return field_.nearest_shape(p); }

  /// A distance (m, may be < 0) that no point of a sphere, cylinder or mesh is nearer to p than, wherever it
  /// lies; arena faces are left out (they are not collisions). The collision early-out rests on it.
  double clearance_lower_bound(const Vec3& p) const { return field_.clearance_lower_bound(p); }

  /// Where the map's moving obstacles are from t = 0 to at least `seconds`: scripted movers exactly, dynamic
  /// bodies as Bullet simulates them (world/bodies/mover_timeline.hpp). Simulated on the first request of a duration
  /// and kept: later requests, from any thread, share it read-only. Null for a map without movers. Without
  /// `with_dynamic`, a timeline of the scripted movers alone (push mode: every run moves the dynamic bodies in
  /// a world of its own, world/bodies/push_world.hpp).
  std::shared_ptr<const MoverTimeline> movers_until(double seconds, bool with_dynamic = true) const;

  /// Bullet's hierarchies of the terrain meshes (world/terrain_shapes.hpp), built on the first request and
  /// shared read-only by every later one, from any thread.
  std::shared_ptr<const TerrainShapes> terrain_shapes() const;
  /// The static geometry's shapes for dynamics worlds (world/bodies/body_physics.hpp), built on the first request and
  /// shared read-only by every push-mode run, from any thread.
  std::shared_ptr<const StaticPhysicsShapes> physics_shapes() const;

  /// True when p lies under a terrain mesh marked solid_below (exact: a vertical ray through its triangles).
  /// Bullet sees only a terrain's surface, so this is how a start buried under a height field is caught.
  bool below_solid_terrain(const Vec3& p) const;

  /// Writes the octree as an OctoMap .bt file (view it with octovis). Written to a temporary file then
  /// renamed, so a crash never leaves half a file. Throws std::runtime_error if it cannot be written.
  void save_octree(const std::filesystem::path& bt_file) const;
  /// Likewise, with the moving obstacles' cells marked where they are at time t (s).
  void save_octree(const std::filesystem::path& bt_file, double t) const;

  /// The octree in OctoMap's binary format (.bt file contents).
  const std::string& octree_data() const { return octree_bt_; }

 private:
  Arena() = default;
  /// Imports the map's meshes (and indexes the solid ones for the start check), counting their triangles.
  void import_meshes();
  /// The distance field and octree over `grid`: read from the cache when it holds them, else built (and stored).
  void load_or_build_field(const VoxelGrid& grid, std::size_t peak_bytes, const BuildOptions& options);

  MapSpec spec_;
  ArenaStats stats_;
  std::vector<TriangleMesh> meshes_;
  DistanceField field_;
  std::string octree_bt_;
  std::vector<VerticalRayIndex> solid_index_;              // per mesh; empty for meshes not solid below
  mutable std::mutex terrain_mutex_;                       // guards terrain_
  mutable std::shared_ptr<const TerrainShapes> terrain_;  // built on the first request
  mutable std::shared_ptr<const StaticPhysicsShapes> physics_shapes_;  // likewise, under terrain_mutex_
  mutable std::mutex movers_mutex_;                        // guards movers_
  mutable std::shared_ptr<const MoverTimeline> movers_;   // the longest timeline simulated so far
  mutable std::shared_ptr<const MoverTimeline> scripted_movers_;  // the same without the dynamic bodies (push mode)
};

/// The default cache folder: $PEG3D_CACHE_DIR, else $XDG_CACHE_HOME/peg3d, else ~/.cache/peg3d.
std::filesystem::path default_cache_dir();

}  // namespace peg3d::world
