// load_map on good maps: every field read as documented, random obstacles placed deterministically with their
// clearances, and the shipped maps (maps/*.yaml) as specified.

#include <cmath>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"
#include "world/map/obstacle_geometry.hpp"
#include "support/numbers.hpp"
#include "world/map/random_obstacles.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

using peg3d::testing::kDeg;

TEST(WorldMapLoader, MinimalMapTakesDefaults) {
  const auto file = testing::data_dir() / "maps" / "minimal.yaml";
  const MapSpec m = load_map(file);
  EXPECT_EQ(m.source, file);
  EXPECT_EQ(m.bounds.lo, Vec3::Zero());
  EXPECT_EQ(m.bounds.hi, Vec3(10, 8, 6));
  EXPECT_DOUBLE_EQ(m.resolution, 0.2);
  EXPECT_DOUBLE_EQ(m.max_distance, 5.0);
  EXPECT_TRUE(m.floor_is_obstacle && m.ceiling_is_obstacle && m.walls_is_obstacle);
  ASSERT_EQ(m.scenarios.size(), 1u);
  EXPECT_EQ(m.scenarios[0].name, "default");
  EXPECT_EQ(m.scenarios[0].pursuers.front().position, Vec3(1, 1, 1));
  EXPECT_FALSE(m.scenarios[0].pursuers.front().heading.has_value());
  ASSERT_TRUE(m.scenarios[0].evaders.front().heading.has_value());
  EXPECT_NEAR(m.scenarios[0].evaders.front().heading->alpha, 90 * kDeg, 1e-12);
  EXPECT_NEAR(m.scenarios[0].evaders.front().heading->theta, 45 * kDeg, 1e-12);
}

TEST(WorldMapLoader, ReadsEveryField) {
  const MapSpec m = load_map(testing::data_dir() / "maps" / "every_field.yaml");
  EXPECT_EQ(m.name, "every field");
  EXPECT_EQ(m.bounds.lo, Vec3(-5, -5, 0));
  EXPECT_EQ(m.bounds.hi, Vec3(15, 15, 10));
  EXPECT_TRUE(m.floor_is_obstacle);
  EXPECT_FALSE(m.ceiling_is_obstacle);
  EXPECT_TRUE(m.walls_is_obstacle);
  EXPECT_DOUBLE_EQ(m.resolution, 0.25);
  EXPECT_DOUBLE_EQ(m.max_distance, 4.0);
  ASSERT_EQ(m.spheres.size(), 1u + 5u);  // explicit first, then generated
  EXPECT_EQ(m.spheres[0].center, Vec3(0, 0, 5));
  EXPECT_DOUBLE_EQ(m.spheres[0].radius, 1.5);
  ASSERT_EQ(m.cylinders.size(), 1u + 4u);
  EXPECT_EQ(m.cylinders[0].base, Vec3(8, 8, 0));
  EXPECT_DOUBLE_EQ(m.cylinders[0].height, 6.0);
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.meshes[0].file, std::filesystem::absolute(testing::mesh_path("ridge.obj")).lexically_normal());
  EXPECT_DOUBLE_EQ(m.meshes[0].scale, 0.5);
  EXPECT_EQ(m.meshes[0].rotation_deg, Vec3(0, 0, 90));
  EXPECT_EQ(m.meshes[0].translation, Vec3(10, 0, 0));
  EXPECT_EQ(m.meshes[0].line, 15);
  ASSERT_EQ(m.scenarios.size(), 2u);
  EXPECT_EQ(m.scenarios[1].name, "second");
  EXPECT_NEAR(m.scenarios[0].pursuers.front().heading->alpha, -90 * kDeg, 1e-12);
  ASSERT_NE(m.find_scenario("second"), nullptr);
  EXPECT_EQ(m.find_scenario("third"), nullptr);
  // Generated spheres: radius in range, inside the region, clear of the starts by 1 m and of each other by 0.5 m.
  for (std::size_t i = 1; i < m.spheres.size(); ++i) {
    const auto& s = m.spheres[i];
    EXPECT_GE(s.radius, 0.3);
    EXPECT_LE(s.radius, 0.6);
    EXPECT_TRUE((s.center.array() - s.radius >= Vec3(-5, -5, 3).array()).all());
    EXPECT_TRUE((s.center.array() + s.radius <= Vec3(5, 5, 10).array()).all());
    for (const auto& sc : m.scenarios) {
      EXPECT_GE(signed_distance(sc.pursuers.front().position, s), 1.0);
      EXPECT_GE(signed_distance(sc.evaders.front().position, s), 1.0);
    }
    for (std::size_t j = 0; j < i; ++j) EXPECT_GE(gap(s, m.spheres[j]), 0.5);
  }
  // Generated cylinders stand on the floor with heights in range.
  for (std::size_t i = 1; i < m.cylinders.size(); ++i) {
    EXPECT_DOUBLE_EQ(m.cylinders[i].base.z(), 0.0);
    EXPECT_DOUBLE_EQ(m.cylinders[i].radius, 0.2);
    EXPECT_GE(m.cylinders[i].height, 2.0);
    EXPECT_LE(m.cylinders[i].height, 3.0);
  }
}

TEST(WorldMapLoader, RandomPlacementIsDeterministic) {
  const auto file = testing::data_dir() / "maps" / "every_field.yaml";
  const MapSpec a = load_map(file), b = load_map(file);
  ASSERT_EQ(a.spheres.size(), b.spheres.size());
  for (std::size_t i = 0; i < a.spheres.size(); ++i) {
    EXPECT_EQ(a.spheres[i].center, b.spheres[i].center);
    EXPECT_EQ(a.spheres[i].radius, b.spheres[i].radius);
  }
}

TEST(WorldMapLoader, SeedChangesPlacement) {
  RandomObstacleSpec g;
  g.count = 5;
  g.radius_min = g.radius_max = 0.5;
  g.region = Box{Vec3::Zero(), Vec3::Constant(10)};
  g.seed = 1;
  const auto a = place_random_obstacles(g, {}, {}, {});
  g.seed = 2;
  const auto b = place_random_obstacles(g, {}, {}, {});
  ASSERT_EQ(a.placed(), 5);
  ASSERT_EQ(b.placed(), 5);
  EXPECT_NE(a.spheres[0].center, b.spheres[0].center);
}

TEST(WorldMapLoader, PlacementKeepsClearanceFromExistingObstacles) {
  RandomObstacleSpec g;
  g.kind = RandomObstacleSpec::Kind::kCylinder;
  g.count = 20;
  g.radius_min = 0.2;
  g.radius_max = 0.4;
  g.height_min = 1;
  g.height_max = 2;
  g.clearance_between = 0.7;
  g.clearance_from_starts = 1.5;
  g.region = Box{Vec3::Zero(), Vec3(10, 10, 5)};
  const std::vector<SphereObstacle> spheres{{Vec3(5, 5, 1), 2.0}};
  const std::vector<Vec3> starts{Vec3(1, 1, 1)};
  const auto placed = place_random_obstacles(g, starts, spheres, {});
  ASSERT_EQ(placed.placed(), 20);
  for (std::size_t i = 0; i < placed.cylinders.size(); ++i) {
    EXPECT_GE(gap(spheres[0], placed.cylinders[i]), 0.7);
    EXPECT_GE(signed_distance(starts[0], placed.cylinders[i]), 1.5);
    for (std::size_t j = 0; j < i; ++j) EXPECT_GE(gap(placed.cylinders[i], placed.cylinders[j]), 0.7);
  }
}

TEST(WorldMapLoader, PaperMapIsThePapersArena) {
  const MapSpec m = load_map(testing::source_dir() / "maps" / "paper.yaml");
  EXPECT_EQ(m.bounds.lo, Vec3::Zero());
  EXPECT_EQ(m.bounds.hi, Vec3(35, 35, 20));
  EXPECT_TRUE(m.floor_is_obstacle && m.ceiling_is_obstacle && m.walls_is_obstacle);
  EXPECT_DOUBLE_EQ(m.resolution, 0.2);
  ASSERT_EQ(m.spheres.size(), 40u);
  EXPECT_TRUE(m.cylinders.empty());
  EXPECT_TRUE(m.meshes.empty());
  const std::vector<std::pair<Vec3, Vec3>> starts{{{5, 30, 1}, {5, 5, 1}},
                                                  {{5, 5, 1}, {30, 30, 1}},
                                                  {{30, 30, 1}, {30, 5, 1}},
                                                  {{30, 30, 1}, {5, 30, 1}}};
  ASSERT_EQ(m.scenarios.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(m.scenarios[i].name, fmt::format("S{}", i + 1));
    EXPECT_EQ(m.scenarios[i].pursuers.front().position, starts[i].first);
    EXPECT_EQ(m.scenarios[i].evaders.front().position, starts[i].second);
  }
  for (std::size_t i = 0; i < m.spheres.size(); ++i) {
    const auto& s = m.spheres[i];
    EXPECT_DOUBLE_EQ(s.radius, 1.0);
    EXPECT_TRUE(m.bounds.shrunk(1.0).contains(s.center));
    for (const auto& sc : m.scenarios) {
      EXPECT_GE(signed_distance(sc.pursuers.front().position, s), 3.0);
      EXPECT_GE(signed_distance(sc.evaders.front().position, s), 3.0);
    }
    for (std::size_t j = 0; j < i; ++j) EXPECT_GE(gap(s, m.spheres[j]), 1.0);
  }
}

TEST(WorldMapLoader, ForestAndValleyMapsLoad) {
  const MapSpec forest = load_map(testing::source_dir() / "maps" / "forest.yaml");
  EXPECT_EQ(forest.cylinders.size(), 152u);
  EXPECT_GE(forest.scenarios.size(), 2u);
  const MapSpec valley = load_map(testing::source_dir() / "maps" / "valley.yaml");
  ASSERT_EQ(valley.meshes.size(), 1u);
  EXPECT_TRUE(valley.meshes[0].solid_below);
  EXPECT_EQ(load_terrain_mesh(valley.meshes[0]).triangle_count(), 3200u);
  EXPECT_GE(valley.scenarios.size(), 2u);
}

TEST(WorldMapLoader, StartsAboveTerrainAreAccepted) {
  // The valley's scenarios lie above the solid terrain: none is reported as inside it.
  const MapSpec valley = load_map(testing::source_dir() / "maps" / "valley.yaml");
  const TriangleMesh terrain = load_terrain_mesh(valley.meshes[0]);
  for (const auto& s : valley.scenarios) {
    EXPECT_FALSE(is_below_surface(terrain, s.pursuers.front().position)) << s.name;
    EXPECT_FALSE(is_below_surface(terrain, s.evaders.front().position)) << s.name;
  }
}

TEST(WorldMapLoader, UnknownKeySuggestsTheNearestKey) {
  testing::ScratchDir dir;
  {
    std::ofstream(dir / "typo.yaml") << "arena:\n  size: [1, 1, 1]\n  faces_are_obstacle: {floor: true}\n"
                                        "start: {pursuer: {position: [0.2, 0.2, 0.2]}, evader: {position: [0.8, 0.8, 0.8]}}\n";
  }
  try {
    load_map(dir / "typo.yaml");
    FAIL();
  } catch (const MapError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("did you mean 'faces_are_obstacles'?"), std::string::npos) << e.what();
  }
}

TEST(WorldMapLoader, TeamsListTheirAgentsWithWhereEachIsWritten) {
  const auto file = testing::source_dir() / "maps" / "pack.yaml";
  const MapSpec m = load_map(file);
  ASSERT_EQ(m.scenarios.size(), 4u);
  const Scenario& s = m.scenarios[0];
  EXPECT_EQ(s.name, "3v2-corners");
  ASSERT_EQ(s.pursuers.size(), 3u);
  ASSERT_EQ(s.evaders.size(), 2u);
  EXPECT_EQ(s.pursuers[2].position, Vec3(5, 17.5, 12));
  EXPECT_EQ(s.pursuers[2].field, "scenarios[0].pursuers[2].position");
  EXPECT_EQ(s.evaders[1].field, "scenarios[0].evaders[1].position");
  EXPECT_GT(s.evaders[1].line, s.pursuers[2].line);
  EXPECT_EQ(m.scenarios[2].agents(), 4);
  // Agents in the game's order: the pursuers, then the evaders.
  EXPECT_EQ(&s.start(2), &s.pursuers[2]);
  EXPECT_EQ(&s.start(3), &s.evaders[0]);
  EXPECT_EQ(&s.start(4), &s.evaders[1]);
  // Obstacles keep their clearance from every agent's start.
  for (const auto& sc : m.scenarios) {
    for (const auto* list : {&sc.pursuers, &sc.evaders}) {
      for (const auto& a : *list) {
        for (const auto& sphere : m.spheres) EXPECT_GE(signed_distance(a.position, sphere), 3.0) << sc.name;
      }
    }
  }
}

TEST(WorldMapLoader, TerrainIsImportedOnceAndHandedToTheArena) {
  const MapSpec m = load_map(testing::source_dir() / "maps" / "valley.yaml");
  ASSERT_FALSE(m.meshes.empty());
  ASSERT_TRUE(m.meshes[0].imported != nullptr);
  const std::size_t triangles = m.meshes[0].imported->triangle_count();
  EXPECT_GT(triangles, 0u);
  // The Arena uses those triangles (the file is not read again) and keeps one copy.
  const auto arena = Arena::build(m);
  EXPECT_EQ(arena->meshes()[0].triangle_count(), triangles);
  EXPECT_EQ(arena->map().meshes[0].imported, nullptr);
}

}  // namespace
}  // namespace peg3d::world
