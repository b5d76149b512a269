// Every file in tests/data/maps/broken/ is a map with one mistake. Its first line says what load_map must
// report:  # expect: LINE FIELD MESSAGE-FRAGMENT   (FIELD "-" for none). Add a case by adding a file.

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

struct Expectation {
  int line = 0;
  std::string field;
  std::string message;
};

Expectation read_expectation(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  static const std::regex pattern(R"(# expect: (\d+) (\S+) (.+))");
  std::smatch m;
  if (!std::regex_match(first, m, pattern)) throw std::runtime_error("no '# expect:' line in " + file.string());
  return {std::stoi(m[1]), m[2] == "-" ? std::string() : std::string(m[2]), m[3]};
}

std::vector<std::string> broken_maps() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(testing::data_dir() / "maps" / "broken")) {
    if (e.path().extension() == ".yaml") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

class WorldBrokenMap : public ::testing::TestWithParam<std::string> {};

TEST_P(WorldBrokenMap, ErrorNamesFileLineAndField) {
  const auto file = testing::data_dir() / "maps" / "broken" / (GetParam() + ".yaml");
  const Expectation want = read_expectation(file);
  try {
    load_map(file);
    FAIL() << "load_map accepted " << file;
  } catch (const MapError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(e.line(), want.line) << what;
    EXPECT_EQ(e.field(), want.field) << what;
    const std::string prefix = file.string() + ":" + std::to_string(want.line) + ": ";
    EXPECT_EQ(what.rfind(prefix, 0), 0u) << what;
    EXPECT_LT(what.size(), file.string().size() + 300) << "quotes the user's text briefly: " << what.substr(0, 500);
    if (!want.field.empty()) {
      EXPECT_NE(what.find(want.field + ": "), std::string::npos) << what;
    }
    EXPECT_NE(what.find(want.message), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, WorldBrokenMap, ::testing::ValuesIn(broken_maps()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(WorldMapErrors, MissingMapFileIsReportedWithoutLine) {
  const auto file = testing::data_dir() / "maps" / "no_such_map.yaml";
  try {
    load_map(file);
    FAIL();
  } catch (const MapError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(std::string(e.what()), file.string() + ": map file not found");
  }
}

TEST(WorldMapErrors, CorpusCoversEveryKindOfError) {
  // The issue's list: syntax, unknown key, missing field, wrong type, non-positive size, NaN, obstacle or start
  // outside, mesh missing / empty / malformed / without triangles / non-finite; scenario names that could
  // name a file outside the results folder, malformed teams, and movers that cannot be (no mass, no period,
  // leaving the arena, starting in an obstacle or on a start, NaN). (A start inside an obstacle is the game's
  // check, with its agents' radii: tests/data/maps/bad-starts/ and game/sim_test.cpp.)
  const auto names = broken_maps();
  for (const char* required : {"syntax_error", "unknown_key", "missing_radius", "wrong_type_size", "zero_size",
                               "negative_radius", "nan_center", "sphere_outside", "start_outside",
                               "mesh_missing", "mesh_empty", "mesh_malformed", "mesh_no_triangles",
                               "mesh_nan_vertex", "scenario_name_climbs_out", "scenario_name_hidden",
                               "team_both_forms", "team_empty_list", "team_not_a_list", "team_missing_evaders",
                               "mover_zero_mass", "mover_zero_period", "mover_path_leaves_arena",
                               "mover_orbit_leaves_arena", "mover_inside_obstacle", "mover_on_a_start",
                               "mover_nan_velocity", "physics_bad_rate"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  }
}

}  // namespace
}  // namespace peg3d::world
