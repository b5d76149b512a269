#include "world/arena.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/hash.hpp"

#include "world/field/field_builder.hpp"
#include "world/map/map_rules.hpp"
#include "world/bodies/mover_timeline.hpp"
#include "world/map/obstacle_geometry.hpp"
#include "world/bodies/body_physics.hpp"
#include "world/terrain_shapes.hpp"
#include "world/field/voxel_grid.hpp"

namespace peg3d::world {

std::filesystem::path default_cache_dir() {
  if (const char* dir = std::getenv("PEG3D_CACHE_DIR"); dir != nullptr && *dir != '\0') return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0') {
    return std::filesystem::path(xdg) / "peg3d";
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
    return std::filesystem::path(home) / ".cache" / "peg3d";
  }
  return std::filesystem::temp_directory_path() / "peg3d-cache";
}

namespace {

// Bump when voxelization, the field or the file layout change: old cache files then simply miss.
constexpr std::uint32_t kCacheFormat = 3;
constexpr char kCacheMagic[8] = {'P', 'E', 'G', '3', 'D', 'W', 'L', 'D'};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Hash of everything the octree and the field depend on: the arena, resolution, cap, boundary faces, every
/// obstacle and every mesh's placed triangles (so edits to a mesh file, or to a glTF's external buffer, miss).
/// Starts and names are left out: editing a scenario does not rebuild the world.
std::uint64_t content_key(const MapSpec& spec, const std::vector<TriangleMesh>& meshes) {
  Fnv1a h;
  h.add_value(kCacheFormat);
  auto add_vec = [&](const Vec3& v) {
    for (int i = 0; i < 3; ++i) h.add_value(v[i]);
  };
  add_vec(spec.bounds.lo);
  add_vec(spec.bounds.hi);
  h.add_value(spec.resolution);
  h.add_value(spec.max_distance);
  h.add_value(static_cast<std::uint8_t>((spec.floor_is_obstacle ? 1 : 0) | (spec.ceiling_is_obstacle ? 2 : 0) |
                                        (spec.walls_is_obstacle ? 4 : 0)));
  h.add_value(spec.spheres.size());
  for (const auto& s : spec.spheres) add_vec(s.center), h.add_value(s.radius);
  h.add_value(spec.cylinders.size());
  for (const auto& c : spec.cylinders) add_vec(c.base), h.add_value(c.radius), h.add_value(c.height);
  h.add_value(meshes.size());
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    h.add_value(static_cast<std::uint8_t>(spec.meshes[i].solid_below));
    h.add_value(meshes[i].vertices.size());
    h.add(meshes[i].vertices.data(), meshes[i].vertices.size() * sizeof(Vec3));
    h.add_value(meshes[i].faces.size());
    h.add(meshes[i].faces.data(), meshes[i].faces.size() * sizeof(meshes[i].faces[0]));
  }
  return h.value();
}

/// Fixed-size header of a cache file.
struct CacheHeader {
  char magic[8];
  std::uint32_t format;
  std::uint32_t cell_bytes;
  std::uint64_t key;
  double resolution;
  double max_distance;
  std::int32_t first[3];
  std::int32_t size[3];
  std::uint64_t occupied_voxels;
  std::uint64_t octree_bytes;
  std::uint64_t cell_count;
};

CacheHeader make_header(std::uint64_t key, const VoxelGrid& grid, double max_distance, std::size_t occupied,
                        std::size_t octree_bytes) {
  CacheHeader h{};
  std::memcpy(h.magic, kCacheMagic, sizeof(h.magic));
  h.format = kCacheFormat;
  h.cell_bytes = sizeof(DistanceField::Cell);
  h.key = key;
  h.resolution = grid.resolution;
  h.max_distance = max_distance;
  for (int a = 0; a < 3; ++a) h.first[a] = grid.first[a], h.size[a] = grid.size[a];
  h.occupied_voxels = occupied;
  h.octree_bytes = octree_bytes;
  h.cell_count = grid.cell_count();
  return h;
}

/// Reads a cache file written for exactly this key and grid; nullopt (with the reason) if it is absent,
/// stale, truncated or unreadable.
struct CachedWorld {
  DistanceField field;
  std::string octree_bt;
  std::size_t occupied_voxels = 0;
};
std::optional<CachedWorld> read_cache(const std::filesystem::path& file, std::uint64_t key, const VoxelGrid& grid,
                                      double max_distance, const Box& arena, ArenaFaces faces, std::string& why) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    why = "miss";
    return std::nullopt;
  }
  std::ifstream in(file, std::ios::binary);
  CacheHeader h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof(h))) {
    why = "unreadable cache file";
    return std::nullopt;
  }
  const CacheHeader want = make_header(key, grid, max_distance, 0, 0);
  const bool same = std::memcmp(h.magic, want.magic, sizeof(h.magic)) == 0 && h.format == want.format &&
                    h.cell_bytes == want.cell_bytes && h.key == want.key && h.resolution == want.resolution &&
                    h.max_distance == want.max_distance && std::memcmp(h.first, want.first, sizeof(h.first)) == 0 &&
                    std::memcmp(h.size, want.size, sizeof(h.size)) == 0 && h.cell_count == want.cell_count;
  const std::uintmax_t expected = sizeof(h) + h.octree_bytes + h.cell_count * sizeof(DistanceField::Cell);
  if (!same || std::filesystem::file_size(file, ec) != expected) {
    why = "stale or truncated cache file";
    return std::nullopt;
  }
  CachedWorld w;
  w.occupied_voxels = h.occupied_voxels;
  w.octree_bt.resize(h.octree_bytes);
  std::vector<DistanceField::Cell> cells(h.cell_count);
  in.read(w.octree_bt.data(), static_cast<std::streamsize>(w.octree_bt.size()));
  in.read(reinterpret_cast<char*>(cells.data()), static_cast<std::streamsize>(cells.size() * sizeof(cells[0])));
  if (!in) {
    why = "unreadable cache file";
    return std::nullopt;
  }
  for (const auto& c : cells) {
    const bool valid = c.x == DistanceField::kNone || (c.x < grid.size[0] && c.y < grid.size[1] && c.z < grid.size[2]);
    if (!valid) {
      why = "corrupt cache file";
      return std::nullopt;
    }
  }
  w.field = DistanceField(grid, max_distance, std::move(cells), arena, faces);
  return w;
}

void write_cache(const std::filesystem::path& file, std::uint64_t key, const DistanceField& field,
                 const std::string& octree_bt, std::size_t occupied) {
  const CacheHeader h = make_header(key, field.grid(), field.max_distance(), occupied, octree_bt.size());
  const auto& cells = field.cells();
  std::filesystem::create_directories(file.parent_path());
  write_file_atomically(file, {std::string_view(reinterpret_cast<const char*>(&h), sizeof(h)), octree_bt,
                               std::string_view(reinterpret_cast<const char*>(cells.data()),
                                                cells.size() * sizeof(cells[0]))});
}

}  // namespace

void Arena::import_meshes() {
  MapSpec& spec = spec_;
  for (std::size_t i = 0; i < spec.meshes.size(); ++i) {
    try {
      meshes_.push_back(spec.meshes[i].imported ? *spec.meshes[i].imported : load_terrain_mesh(spec.meshes[i]));
      spec.meshes[i].imported.reset();  // the Arena keeps one copy of the triangles
    } catch (const MeshError& e) {
      throw MapError(spec.source, spec.meshes[i].line, fmt::format("terrain[{}].file", i), e.what());
    }
    stats_.triangles += meshes_.back().triangle_count();
    // Starts are checked against solid terrain at every reset: index the triangles once.
    solid_index_.push_back(spec.meshes[i].solid_below ? VerticalRayIndex(meshes_.back()) : VerticalRayIndex());
  }
}

void Arena::load_or_build_field(const VoxelGrid& grid, std::size_t peak, const BuildOptions& options) {
  const MapSpec& spec = spec_;
  ArenaStats& st = stats_;
  const ArenaFaces faces{spec.floor_is_obstacle, spec.ceiling_is_obstacle, spec.walls_is_obstacle};
  st.cache_key = content_key(spec, meshes_);
  st.cache_status = "off";
  if (options.cache_dir) {
    st.cache_file = *options.cache_dir / fmt::format("{:016x}.pegworld", st.cache_key);
    std::string why;
    if (auto cached = read_cache(st.cache_file, st.cache_key, grid, spec.max_distance, spec.bounds, faces, why)) {
      field_ = std::move(cached->field);
      octree_bt_ = std::move(cached->octree_bt);
      st.occupied_voxels = cached->occupied_voxels;
      st.loaded_from_cache = true;
      st.cache_status = "hit";
      return;
    }
    st.cache_status = why;
  }
  st.build_peak_bytes = peak;
  const auto tv = std::chrono::steady_clock::now();
  Occupancy occupancy(grid);
  for (const auto& s : spec.spheres) occupancy.add_sphere(s);
  for (const auto& c : spec.cylinders) occupancy.add_cylinder(c);
  for (std::size_t i = 0; i < meshes_.size(); ++i) occupancy.add_mesh(meshes_[i], spec.meshes[i].solid_below);
  st.voxelize_seconds = seconds_since(tv);

  FieldBuild built = build_distance_field(occupancy, spec.max_distance, spec.bounds, faces);
  field_ = std::move(built.field);
  octree_bt_ = std::move(built.octree_bt);
  st.occupied_voxels = built.occupied_voxels;
  st.octree_seconds = built.octree_seconds;
  st.edt_seconds = built.edt_seconds;
  if (options.cache_dir) {
    try {
      write_cache(st.cache_file, st.cache_key, field_, octree_bt_, st.occupied_voxels);
      st.cache_status = st.cache_status == "miss" ? "stored" : st.cache_status + "; stored";
    } catch (const std::exception& e) {
      st.cache_status = fmt::format("not stored ({})", e.what());  // a read-only cache must not stop a run
    }
  }
}

std::shared_ptr<const Arena> Arena::build(const MapSpec& spec_in, const BuildOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  std::shared_ptr<Arena> arena(new Arena());
  arena->spec_ = spec_in;
  MapSpec& spec = arena->spec_;
  if (options.resolution_override) spec.resolution = *options.resolution_override;
  validate_map(spec);

  ArenaStats& st = arena->stats_;
  st.resolution = spec.resolution;
  st.spheres = spec.spheres.size();
  st.cylinders = spec.cylinders.size();
  st.meshes = spec.meshes.size();
  arena->import_meshes();
  validate_movers(spec, arena->meshes_);

  const VoxelGrid grid = VoxelGrid::around(spec.bounds, spec.resolution);
  st.field_dims = grid.size;
  st.field_cells = grid.cell_count();
  const std::size_t peak = estimate_build_bytes(grid);
  if (peak > options.max_field_bytes) {
    throw MapError(spec.source, 0, "occupancy.resolution",
                   fmt::format("a distance field at {} m has {} cells and needs about {:.0f} MiB to build, more than "
                               "the limit of {:.0f} MiB; use a coarser resolution",
                               spec.resolution, grid.cell_count(), peak / 1048576.0,
                               options.max_field_bytes / 1048576.0));
  }
  arena->load_or_build_field(grid, peak, options);
  st.field_bytes = arena->field_.bytes();
  st.octree_bytes = arena->octree_bt_.size();
  st.build_seconds = seconds_since(t0);
  return arena;
}

std::shared_ptr<const MoverTimeline> Arena::movers_until(double seconds, bool with_dynamic) const {
  if (spec_.movers.empty()) return nullptr;
  const std::lock_guard lock(movers_mutex_);
  // Simulating further from the same start reproduces the shorter run's substeps exactly, so a longer timeline
  // serves every shorter request.
  auto& cached = with_dynamic ? movers_ : scripted_movers_;
  if (!cached || cached->duration() < seconds) {
    cached = std::make_shared<const MoverTimeline>(spec_, meshes_, seconds, MoverTimeline::kMaxBytes, with_dynamic);
  }
  return cached;
}

void Arena::save_octree(const std::filesystem::path& bt_file, double t) const {
  const auto movers = movers_until(t);
  if (!movers) return save_octree(bt_file);
  std::vector<std::pair<Shape, Pose>> shapes;
  for (int m = 0; m < movers->count(); ++m) shapes.emplace_back(movers->mover(m).shape, movers->pose(m, t));
  std::error_code ignored;
  if (bt_file.has_parent_path()) std::filesystem::create_directories(bt_file.parent_path(), ignored);
  write_file_atomically(bt_file, {std::string_view(octree_with_shapes(octree_bt_, field_.grid(), shapes))});
}

std::shared_ptr<const TerrainShapes> Arena::terrain_shapes() const {
  const std::lock_guard lock(terrain_mutex_);
  if (!terrain_) terrain_ = std::make_shared<const TerrainShapes>(meshes_);
  return terrain_;
}

std::shared_ptr<const StaticPhysicsShapes> Arena::physics_shapes() const {
  const std::lock_guard lock(terrain_mutex_);
  if (!physics_shapes_) physics_shapes_ = make_static_physics_shapes(spec_, meshes_);
  return physics_shapes_;
}

bool Arena::below_solid_terrain(const Vec3& p) const {
  for (std::size_t i = 0; i < meshes_.size(); ++i) {
    if (spec_.meshes[i].solid_below && solid_index_[i].is_below_surface(meshes_[i], p)) return true;
  }
  return false;
}

void Arena::save_octree(const std::filesystem::path& bt_file) const {
  std::error_code ignored;  // a folder that cannot be made shows up as the writer's error, naming the file
  if (bt_file.has_parent_path()) std::filesystem::create_directories(bt_file.parent_path(), ignored);
  write_file_atomically(bt_file, {std::string_view(octree_bt_)});
}

}  // namespace peg3d::world
