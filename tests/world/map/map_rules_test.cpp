// The map rules, shared by load_map and by maps written in code (Arena::build): a map built in code gets the
// same checks as a file, named by its field.
#include "world/map/map_rules.hpp"

#include <gtest/gtest.h>

#include "world/arena.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

void expect_rejected(const MapSpec& spec, const std::string& field, const std::string& fragment) {
  try {
    validate_map(spec);
    ADD_FAILURE() << "accepted; expected " << field;
  } catch (const MapError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
  EXPECT_THROW(Arena::build(spec), MapError) << field;
}

TEST(WorldMapRules, MapsBuiltInCodeAreCheckedLikeFiles) {
  const MapSpec ok = testing::empty_spec(Vec3::Constant(10), 0.25);
  EXPECT_NO_THROW(validate_map(ok));
  MapSpec m = ok;
  m.spheres.push_back({Vec3(5, 5, 5), -1.0});
  expect_rejected(m, "spheres[0].radius", "must be > 0, got -1");
  m = ok;
  m.cylinders.push_back({Vec3(50, 5, 0), 1.0, 2.0});
  expect_rejected(m, "cylinders[0].base", "outside the arena");
  m = ok;
  m.resolution = 20.0;
  expect_rejected(m, "occupancy.resolution", "coarser than the arena");
  m = ok;
  m.max_distance = 0.1;
  expect_rejected(m, "occupancy.max_distance", "must be >= occupancy.resolution");
  m = ok;
  m.scenarios[0].name = "../../x";
  expect_rejected(m, "scenarios[0].name", "cannot name a scenario");
  m = ok;
  m.scenarios.push_back(m.scenarios[0]);
  expect_rejected(m, "scenarios[1].name", "duplicate scenario name");
  m = ok;
  m.scenarios[0].evaders.clear();
  expect_rejected(m, "scenarios[0].evaders", "at least one evader");
  m = ok;
  m.scenarios[0].pursuers[0].position = Vec3(-1, 5, 5);
  expect_rejected(m, "scenarios[0].pursuers[0].position", "outside the arena");
}

TEST(WorldMapRules, SafeNamesCannotLeaveAFolder) {
  for (const char* good : {"S1", "3v2-corners", "a.b_c", "x"}) EXPECT_TRUE(is_safe_name(good)) << good;
  for (const char* bad : {"", "..", ".hidden", "../x", "a/b", "a\\b", "a b", "C:", "a\nb"}) {
    EXPECT_FALSE(is_safe_name(bad)) << bad;
  }
  EXPECT_FALSE(is_safe_name(std::string(65, 'a')));
  EXPECT_TRUE(is_safe_name(std::string(64, 'a')));
}

}  // namespace
}  // namespace peg3d::world
