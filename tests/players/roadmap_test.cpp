#include "players/roadmap.hpp"

#include <random>

#include <gtest/gtest.h>

#include "solids_probe.hpp"

namespace peg3d::players {
namespace {

using peg3d::testing::BoxesProbe;
using peg3d::testing::wall_with_hole;

const Box kArena{{0, 0, 0}, {20, 20, 8}};

// Flies from `from` towards the roadmap's waypoints in steps of `step` (m) until within a step of `to`; every step
// must be clear of the solids. Returns the length flown (infinite when it does not arrive within `budget` m, or
// within as many steps).
double fly(Roadmap& map, const BoxesProbe& probe, Vec3 from, const Vec3& to, double step, double budget) {
  double flown = 0.0;
  for (int steps = 0; (to - from).norm() > step; ++steps) {
    if (steps > budget / step) return std::numeric_limits<double>::infinity();  // stuck (a waypoint where it is)
    const auto way = map.waypoint(probe, from, to, kPassage);
    if (!way) return std::numeric_limits<double>::infinity();
    const Vec3 d = *way - from;
    const Vec3 next = from + std::min(step, d.norm()) * d.normalized();
    EXPECT_TRUE(probe.clear(from, next)) << from.transpose() << " -> " << next.transpose();
    flown += (next - from).norm();
    from = next;
    if (flown > budget) return std::numeric_limits<double>::infinity();
  }
  return flown + (to - from).norm();
}

TEST(Roadmap, PassableNeedsTheLineAndItsFourSidesClear) {
  const BoxesProbe probe = wall_with_hole(13.0, 2.0);
  EXPECT_TRUE(passable(probe, {15, 13, 4}, {5, 13, 4}, 0.8));   // through the middle of the opening
  EXPECT_FALSE(passable(probe, {15, 13, 4}, {5, 13, 4}, 1.1));  // a margin wider than half the opening
  EXPECT_FALSE(passable(probe, {15, 13.5, 4}, {5, 13.5, 4}, 0.8));  // 0.5 m off the middle: one side grazes
  EXPECT_FALSE(passable(probe, {15, 5, 4}, {5, 5, 4}, 0.1));
  EXPECT_TRUE(passable(probe, {15, 5, 4}, {12, 5, 4}, 0.8));  // not reaching the wall
}

TEST(Roadmap, AWayThroughTheOnlyOpeningIsNearlyTheShortest) {
  // From random points east of the wall to random points west of it, the opening placed at random: flying to the
  // waypoints gets there without touching the wall, within 15 % of the shortest way (through the opening's
  // nearest point, a bound from below) plus a cell.
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> east(12.0, 19.0), west(1.0, 8.0), y(1.0, 19.0), z(1.0, 7.0), hole(3.0, 17.0);
  for (int trial = 0; trial < 40; ++trial) {
    const double h = hole(rng);
    const BoxesProbe probe = wall_with_hole(h, 2.0);
    Roadmap map;
    map.build(kArena, probe);
    const Vec3 a(east(rng), y(rng), z(rng)), b(west(rng), y(rng), z(rng));
    // The shortest way bends at most at the opening's edges: no shorter than through the opening's rectangle
    // y in [h - 1, h + 1] on the plane x = 10 at its best point.
    double shortest = std::numeric_limits<double>::infinity();
    for (double yy = h - 1.0; yy <= h + 1.0; yy += 0.01) {
      const Vec3 m(10.0, yy, 0.5 * (a.z() + b.z()));
      shortest = std::min(shortest, (m - a).norm() + (b - m).norm());
    }
    const double flown = fly(map, probe, a, b, 0.1, 3.0 * shortest);
    EXPECT_LT(flown, 1.15 * shortest + Roadmap::kCell) << "hole " << h << " from " << a.transpose() << " to " << b.transpose();
  }
}

TEST(Roadmap, AGoalInsideAClosedRoomHasNoWayAndOneOutsideItHas) {
  BoxesProbe probe;  // a room x, y in 6-14 m, z 0-6 m, walls 1 m thick, closed all round
  probe.solids = {Box{{6, 6, 0}, {7, 14, 6}}, Box{{13, 6, 0}, {14, 14, 6}}, Box{{6, 6, 0}, {14, 7, 6}},
                  Box{{6, 13, 0}, {14, 14, 6}}, Box{{6, 6, 5}, {14, 14, 6}}};
  Roadmap map;
  map.build(kArena, probe);
  EXPECT_NE(map.region(map.cell_of({10, 10, 2.5})), map.region(map.cell_of({2, 2, 2})));
  EXPECT_FALSE(map.waypoint(probe, {2, 2, 2}, {10, 10, 2.5}, kPassage).has_value());
  EXPECT_TRUE(map.waypoint(probe, {2, 2, 2}, {18, 18, 2}, kPassage).has_value());
  EXPECT_EQ(map.region(map.cell_of({6.5, 10, 2})), -1);  // in the wall
  // A goal in the wall's cell is taken at an open neighbour on the start's side.
  const auto way = map.waypoint(probe, {2, 10, 2}, {6.2, 10, 2.5}, kPassage);
  ASSERT_TRUE(way.has_value());
  EXPECT_LT(way->x(), 6.0);
}

TEST(Roadmap, TheSameQuestionGetsTheSameAnswerWhateverWasAskedBefore) {
  const BoxesProbe probe = wall_with_hole(6.0, 2.0);
  Roadmap asked, fresh;
  asked.build(kArena, probe);
  const Vec3 a(16, 15, 3), b(3, 16, 4), c(4, 2, 2), d(17, 2, 6);
  (void)asked.waypoint(probe, a, c, kPassage);
  (void)asked.waypoint(probe, d, b, kPassage);
  const auto again = asked.waypoint(probe, a, b, kPassage);
  fresh.build(kArena, probe);
  const auto first = fresh.waypoint(probe, a, b, kPassage);
  ASSERT_TRUE(again && first);
  EXPECT_EQ(*again, *first);
  EXPECT_EQ(*fresh.waypoint(probe, a, b, kPassage), *first);  // the kept way
}

TEST(Roadmap, InTheOpenTheWaypointIsTheGoalWhenItIsWithinTheLookAhead) {
  const BoxesProbe open;
  Roadmap map;
  map.build(kArena, open);
  std::mt19937_64 rng(54);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 a(10 + 4 * u(rng), 10 + 4 * u(rng), 4 + 2 * u(rng));
    const Vec3 b = a + 2.5 * Vec3(u(rng), u(rng), 0.5 * u(rng));
    const auto way = map.waypoint(open, a, b, kPassage);
    ASSERT_TRUE(way.has_value());
    EXPECT_EQ(*way, b);
  }
}

TEST(Roadmap, ALargeArenaGetsWiderCellsWithinTheCap) {
  const BoxesProbe open;
  Roadmap map;
  map.build({{0, 0, 0}, {1000, 1000, 100}}, open);
  EXPECT_LE(map.cells(), Roadmap::kMaxCells);
  EXPECT_GT(map.cells(), Roadmap::kMaxCells / 4);
  map.build(kArena, open);
  EXPECT_EQ(map.cells(), 20 * 20 * 8);
}

}  // namespace
}  // namespace peg3d::players
