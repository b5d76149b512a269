// Arena: statistics, the on-disk cache (hit, key, stale and truncated files), the .bt export read back by
// OctoMap, and the refusal of fields that would not fit in memory.

#include <fstream>

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include "world/arena.hpp"
#include "world/map/map_loader.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

using testing::ScratchDir;

MapSpec small_world() {
  MapSpec spec = testing::empty_spec(Vec3(8, 6, 5), 0.25, 2.0);
  spec.spheres.push_back({Vec3(2, 2, 2), 0.8});
  spec.cylinders.push_back({Vec3(6, 4, 0), 0.5, 3.0});
  spec.meshes.push_back(testing::mesh_entry("wall.obj", Vec3(4, 3, 0), 0.4));
  spec.floor_is_obstacle = true;
  return spec;
}

BuildOptions cached_in(const ScratchDir& dir) {
  BuildOptions o;
  o.cache_dir = dir.path();
  return o;
}

TEST(WorldArena, StatsDescribeTheBuild) {
  const auto arena = testing::build(small_world());
  const ArenaStats& s = arena->stats();
  EXPECT_EQ(s.spheres, 1u);
  EXPECT_EQ(s.cylinders, 1u);
  EXPECT_EQ(s.meshes, 1u);
  EXPECT_EQ(s.triangles, 2u);
  EXPECT_EQ(s.resolution, 0.25);
  EXPECT_EQ(s.field_dims, (std::array<int, 3>{34, 26, 22}));
  EXPECT_EQ(s.field_cells, 34u * 26u * 22u);
  EXPECT_EQ(s.field_bytes, s.field_cells * 6);
  EXPECT_GT(s.occupied_voxels, 34u * 26u);  // at least the floor layer
  EXPECT_GT(s.build_seconds, 0.0);
  EXPECT_FALSE(s.loaded_from_cache);
  EXPECT_EQ(s.cache_status, "off");
  EXPECT_EQ(arena->meshes().size(), 1u);
}

TEST(WorldArena, SecondBuildLoadsFromTheCache) {
  ScratchDir dir;
  const auto first = Arena::build(small_world(), cached_in(dir));
  EXPECT_FALSE(first->stats().loaded_from_cache);
  EXPECT_EQ(first->stats().cache_status, "stored");
  ASSERT_TRUE(std::filesystem::exists(first->stats().cache_file));
  const auto second = Arena::build(small_world(), cached_in(dir));
  EXPECT_TRUE(second->stats().loaded_from_cache);
  EXPECT_EQ(second->stats().cache_status, "hit");
  EXPECT_EQ(second->stats().occupied_voxels, first->stats().occupied_voxels);
  EXPECT_EQ(second->octree_data(), first->octree_data());
  const auto& a = first->distance_field().cells();
  const auto& b = second->distance_field().cells();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])), 0);
  // No temporary files are left next to the cache file.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(WorldArena, CacheKeyFollowsWhatShapesTheWorld) {
  const MapSpec base = small_world();
  const auto key = testing::build(base)->stats().cache_key;
  MapSpec moved = base;
  moved.spheres[0].center.x() += 0.01;
  EXPECT_NE(testing::build(moved)->stats().cache_key, key);
  BuildOptions finer;
  finer.resolution_override = 0.2;
  EXPECT_NE(Arena::build(base, finer)->stats().cache_key, key);
  MapSpec ceiling = base;
  ceiling.ceiling_is_obstacle = true;
  EXPECT_NE(testing::build(ceiling)->stats().cache_key, key);
  // Scenarios do not shape the world: editing them keeps the cache.
  MapSpec other_start = base;
  other_start.scenarios[0].pursuers.front().position = Vec3(1, 5, 4);
  EXPECT_EQ(testing::build(other_start)->stats().cache_key, key);
}

TEST(WorldArena, CacheKeyFollowsTheMeshFileContents) {
  ScratchDir dir;
  std::filesystem::copy_file(testing::mesh_path("wall.obj"), dir / "wall.obj");
  MapSpec spec = small_world();
  spec.meshes[0].file = dir / "wall.obj";
  const auto key = testing::build(spec)->stats().cache_key;
  std::ofstream(dir / "wall.obj", std::ios::app) << "v 0 0 0\nv 0 1 0\nv 0 0 1\nf 5 6 7\n";
  const auto edited = testing::build(spec);
  EXPECT_NE(edited->stats().cache_key, key);
  EXPECT_EQ(edited->stats().triangles, 3u);
}

TEST(WorldArena, TruncatedOrStaleCacheFileIsRebuilt) {
  ScratchDir dir;
  const auto first = Arena::build(small_world(), cached_in(dir));
  const auto file = first->stats().cache_file;
  std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
  const auto second = Arena::build(small_world(), cached_in(dir));
  EXPECT_FALSE(second->stats().loaded_from_cache);
  EXPECT_NE(second->stats().cache_status.find("truncated"), std::string::npos) << second->stats().cache_status;
  // Rebuilt and stored again: the third build hits.
  EXPECT_TRUE(Arena::build(small_world(), cached_in(dir))->stats().loaded_from_cache);
  // Garbage with the right name is not trusted either.
  std::ofstream(file, std::ios::trunc) << "not a cache file";
  EXPECT_FALSE(Arena::build(small_world(), cached_in(dir))->stats().loaded_from_cache);
}

TEST(WorldArena, UnwritableCacheDoesNotStopTheBuild) {
  ScratchDir dir;
  std::ofstream(dir / "blocker") << "a file where the cache folder should be";
  BuildOptions o;
  o.cache_dir = dir / "blocker" / "cache";
  const auto arena = Arena::build(small_world(), o);
  EXPECT_FALSE(arena->stats().loaded_from_cache);
  EXPECT_NE(arena->stats().cache_status.find("not stored"), std::string::npos) << arena->stats().cache_status;
  EXPECT_TRUE(arena->nearest_obstacle(Vec3(2, 2, 3.5)).found);
}

TEST(WorldArena, OctreeExportReadsBackInOctomap) {
  ScratchDir dir;
  const auto arena = testing::build(small_world());
  arena->save_octree(dir / "world.bt");
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary((dir / "world.bt").string()));
  EXPECT_DOUBLE_EQ(tree.getResolution(), 0.25);
  auto occupied = [&](const Vec3& p) {
    const octomap::OcTreeNode* n = tree.search(p.x(), p.y(), p.z());
    return n != nullptr && tree.isNodeOccupied(n);
  };
  EXPECT_TRUE(occupied(Vec3(2, 2, 2)));        // sphere centre
  EXPECT_TRUE(occupied(Vec3(2.75, 2, 2)));     // near its surface
  EXPECT_TRUE(occupied(Vec3(6, 4, 2.9)));      // inside the cylinder
  EXPECT_TRUE(occupied(Vec3(4, 3, 1)));        // on the wall mesh
  EXPECT_TRUE(occupied(Vec3(7, 1, -0.1)));     // the floor layer
  EXPECT_FALSE(occupied(Vec3(7, 1, 4)));       // free space
  EXPECT_FALSE(occupied(Vec3(2, 2, 3.1)));
  // Written atomically: only the .bt file is there.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(WorldArena, SaveOctreeToAnUnwritablePathThrows) {
  const auto arena = testing::build(small_world());
  EXPECT_THROW(arena->save_octree("/proc/peg3d-cannot-write-here/x.bt"), std::runtime_error);
}

TEST(WorldArena, RefusesFieldsLargerThanTheLimit) {
  BuildOptions o;
  o.max_field_bytes = 100 << 10;
  try {
    Arena::build(small_world(), o);
    FAIL();
  } catch (const MapError& e) {
    EXPECT_EQ(e.field(), "occupancy.resolution");
    EXPECT_NE(std::string(e.what()).find("coarser resolution"), std::string::npos) << e.what();
  }
}

TEST(WorldArena, RejectsBadSpecsBuiltInCode) {
  MapSpec spec = small_world();
  spec.spheres[0].radius = -1;
  EXPECT_THROW(testing::build(spec), MapError);
  spec = small_world();
  BuildOptions o;
  o.resolution_override = 0.0;
  EXPECT_THROW(Arena::build(spec, o), MapError);
  spec.meshes[0].file = testing::mesh_path("empty.obj");
  try {
    testing::build(spec);
    FAIL();
  } catch (const MapError& e) {
    EXPECT_EQ(e.field(), "terrain[0].file");
  }
}

TEST(WorldArena, PaperMapBuildsAtItsResolution) {
  const auto arena = testing::build(load_map(testing::source_dir() / "maps" / "paper.yaml"));
  EXPECT_EQ(arena->stats().field_dims, (std::array<int, 3>{177, 177, 102}));
  // The starts sit 1 m above the floor, which is the nearest obstacle.
  for (const auto& s : arena->map().scenarios) {
    const NearestObstacle n = arena->nearest_obstacle(s.pursuers.front().position);
    EXPECT_TRUE(n.found);
    EXPECT_NEAR(n.distance, 1.0, 1e-9) << s.name;
  }
}

}  // namespace
}  // namespace peg3d::world
