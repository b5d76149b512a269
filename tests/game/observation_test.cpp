// The observation's entries (game/observation.hpp): each name in kObservationEntries is the quantity
// observation_base writes at that place, and each entry's bounds hold what it can take.
#include "game/observation.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace peg3d::game {
namespace {

// A view whose every quantity is distinct, and what each entry's name says it holds.
TEST(ObservationVector, EachNamedEntryHoldsItsQuantity) {
  AgentView v;
  v.percept.target_distance = 11.5;
  v.percept.target = {0.25, -0.5};
  v.percept.obstacle.distance = 3.75;
  v.percept.to_obstacle = {1.25, -1.5};
  v.self.position = {4.0, 5.0, 6.0};
  v.self.heading = {0.75, 1.75};
  v.other.position = {12.0, 3.0, 7.5};
  v.other.heading = {0.0, kPi / 2};  // along +x
  v.other_speed = 2.0;
  v.field = {2.3, Vec3(4.5, 6.0, 4.0), true};
  const std::map<std::string, double> expected{
      {"target_distance", 11.5},     {"target_azimuth_error", 0.25},    {"target_elevation_error", -0.5},
      {"obstacle_distance", 3.75},   {"obstacle_azimuth_error", 1.25},  {"obstacle_elevation_error", -1.5},
      {"x", 4.0},                    {"y", 5.0},                        {"z", 6.0},
      {"alpha", 0.75},               {"theta", 1.75},                   {"opponent_dx", 8.0},
      {"opponent_dy", -2.0},         {"opponent_dz", 1.5},              {"opponent_vx", 2.0},
      {"opponent_vy", 0.0},          {"opponent_vz", 0.0},              {"obstacle_dx", 0.5},
      {"obstacle_dy", 1.0},          {"obstacle_dz", -2.0}};
  float o[kObservationBase];
  observation_base(v, o);
  ASSERT_EQ(expected.size(), kObservationEntries.size());
  for (int k = 0; k < kObservationBase; ++k) {
    const ObservationEntry& e = kObservationEntries[std::size_t(k)];
    ASSERT_TRUE(expected.count(e.name)) << e.name;
    EXPECT_NEAR(o[k], expected.at(e.name), 1e-6) << "entry " << k << " (" << e.name << ")";
  }
}

TEST(ObservationVector, BoundsFollowTheArenaTheReachAndTheSpeed) {
  const Box box{Vec3(-1, 2, 0), Vec3(34, 37, 20)};
  const double reach = 52.0, speed = 1.5;
  const std::map<std::string, std::pair<double, double>> expected{
      {"target_distance", {0, reach}}, {"alpha", {-kPi, kPi}},  {"theta", {0, kPi}},      {"x", {-1, 34}},
      {"y", {2, 37}},                  {"z", {0, 20}},          {"opponent_dx", {-35, 35}}, {"opponent_dz", {-20, 20}},
      {"opponent_vy", {-speed, speed}}, {"obstacle_dz", {-reach, reach}}, {"obstacle_elevation_error", {-kPi, kPi}}};
  for (const ObservationEntry& e : kObservationEntries) {
    if (!expected.count(e.name)) continue;
    EXPECT_EQ(entry_bounds(e.range, box, reach, speed), expected.at(e.name)) << e.name;
  }
}

}  // namespace
}  // namespace peg3d::game
