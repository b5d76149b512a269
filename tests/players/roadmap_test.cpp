#include "players/roadmap.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

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

// Each open cell's distance from `source` along ways through open cells of kArena's 1 m grid (26 neighbours), found
// by relaxing every cell until nothing changes: the reference the partition is checked against. With `rival`, the
// time at `pace` (s/m) along ways through cells reached before the rival's time there (the rival's time of a cell
// given per cell).
std::vector<double> way_lengths(const Roadmap& map, const Vec3& source, double pace = 1.0,
                                const std::vector<double>* rival = nullptr) {
  const int n = map.cells();
  std::vector<double> d(std::size_t(n), std::numeric_limits<double>::infinity());
  const int start = map.cell_of(source);
  d[std::size_t(start)] = (source - map.centre(start)).norm() * pace;
  for (bool changed = true; changed;) {
    changed = false;
    for (int c = 0; c < n; ++c) {
      if (c != start && map.region(c) < 0) continue;
      if (rival != nullptr && !(d[std::size_t(c)] < (*rival)[std::size_t(c)])) continue;
      for (int o = 0; o < 27; ++o) {
        const int i = c % 20 + o % 3 - 1, j = (c / 20) % 20 + (o / 3) % 3 - 1, k = c / 400 + o / 9 - 1;
        if (o == 13 || i < 0 || j < 0 || k < 0 || i >= 20 || j >= 20 || k >= 8) continue;
        const int next = i + 20 * (j + 20 * k);
        const double via = d[std::size_t(c)] + (map.centre(next) - map.centre(c)).norm() * pace;
        if (map.region(next) >= 0 && via < d[std::size_t(next)] - 1e-12) d[std::size_t(next)] = via, changed = true;
      }
    }
  }
  return d;
}

// Five sources in kArena: the first anywhere, the others anywhere or, when `near`, within `spread` (m) of it along each
// axis, so that its cells are few and the partition's search stops early.
std::vector<Vec3> random_sources(std::mt19937_64& rng, bool near, double spread) {
  std::uniform_real_distribution<double> x(0.2, 19.8), z(0.2, 7.8), off(-spread, spread);
  std::vector<Vec3> sources = {{x(rng), x(rng), z(rng)}};
  for (int s = 1; s < 5; ++s) {
    const Vec3 d = near ? Vec3(off(rng), off(rng), off(rng)) : Vec3(x(rng), x(rng), z(rng)) - sources[0];
    sources.push_back(kArena.clamp(sources[0] + d));
  }
  return sources;
}

TEST(Roadmap, ThePartitionGivesEachCellNearTheFirstSourceToTheSourceWithTheShortestWay) {
  // Random sources round a wall with a hole at a random place: every cell of the first source's, and every cell
  // sharing a face with one, belongs to the source whose way to it is the shortest (the reference above), but where
  // two ways tie.
  std::mt19937_64 rng(55);
  std::uniform_real_distribution<double> hole(3.0, 17.0);
  int checked = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const BoxesProbe probe = wall_with_hole(hole(rng), 2.0);
    Roadmap map;
    map.build(kArena, probe);
    const std::vector<Vec3> sources = random_sources(rng, trial % 2 == 1, 3.0);
    map.partition(sources);
    std::vector<std::vector<double>> d;
    for (const Vec3& s : sources) d.push_back(way_lengths(map, s));
    for (int c = 0; c < map.cells(); ++c) {
      bool near_first = map.owner(c) == 0;
      for (int step : {1, -1, 20, -20, 400, -400}) {
        const int next = c + step;
        const bool same_row = std::abs(step) != 1 || next / 20 == c / 20;
        const bool same_layer = std::abs(step) != 20 || next / 400 == c / 400;
        if (next >= 0 && next < map.cells() && same_row && same_layer && map.owner(next) == 0) near_first = true;
      }
      if (!near_first || map.region(c) < 0) continue;
      double best = std::numeric_limits<double>::infinity(), second = best;
      int owner = -1;
      for (std::size_t s = 0; s < sources.size(); ++s) {
        const double ds = d[s][std::size_t(c)];
        if (ds < best) second = best, best = ds, owner = int(s);
        else second = std::min(second, ds);
      }
      if (second - best < 1e-9) continue;  // a tie: either may have it
      EXPECT_EQ(map.owner(c), owner) << "trial " << trial << " cell " << map.centre(c).transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(Roadmap, AFasterFirstSourceTakesTheCellsItReachesFirstThroughItsOwn) {
  // As above with the first source 1.3 and 2 times as fast as the others: its cells are those it reaches before all
  // of them (their shortest ways) along ways through its own cells (the reference with a rival), but where the two
  // times tie. Slower ways through its cells could not have taken any of them from it, so the others' ways need no
  // such limit.
  std::mt19937_64 rng(60);
  std::uniform_real_distribution<double> hole(3.0, 17.0);
  int checked = 0, taken = 0, beyond = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const double speed = trial % 3 == 2 ? 2.0 : 1.3;
    const BoxesProbe probe = wall_with_hole(hole(rng), 2.0);
    Roadmap map;
    map.build(kArena, probe);
    const std::vector<Vec3> sources = random_sources(rng, trial % 2 == 1, 4.0);
    std::vector<double> others(std::size_t(map.cells()), std::numeric_limits<double>::infinity());
    for (std::size_t s = 1; s < sources.size(); ++s) {
      const std::vector<double> d = way_lengths(map, sources[s]);
      for (std::size_t c = 0; c < d.size(); ++c) others[c] = std::min(others[c], d[c]);
    }
    const std::vector<double> first = way_lengths(map, sources[0], 1.0 / speed, &others);
    map.partition(sources);
    std::vector<int> equal(std::size_t(map.cells()));
    for (int c = 0; c < map.cells(); ++c) equal[std::size_t(c)] = map.owner(c);
    Roadmap faster;  // the same solids and sources asked at another speed first: its answer is not this one's
    faster.build(kArena, probe);
    faster.partition(sources, 3.0);
    map.partition(sources, speed);
    for (int c = 0; c < map.cells(); ++c) {
      if (map.region(c) < 0 && c != map.cell_of(sources[0])) continue;
      const double t = first[std::size_t(c)], rival = others[std::size_t(c)];
      if (std::isfinite(t) && std::abs(t - rival) < 1e-9) continue;  // a tie: either may have it
      EXPECT_EQ(map.owner(c) == 0, t < rival) << "trial " << trial << " cell " << map.centre(c).transpose();
      ++checked;
      taken += map.owner(c) == 0;
      beyond += map.owner(c) == 0 && equal[std::size_t(c)] != 0;
    }
  }
  EXPECT_GT(checked, 10000);
  EXPECT_GT(taken, 1000);
  EXPECT_GT(beyond, 500);  // cells it has at its speed and not at the others'
}

TEST(Roadmap, AcrossAWallTheBorderIsWhereTheWayRoundMeetsNotTheStraightBisector) {
  // The evader west of a wall whose only hole is at y = 17; one pursuer just east of it, 3 m away straight through
  // the wall, another west 8 m away. Straight, the east pursuer would share a face with the evader on the wall;
  // by the ways round, the west pursuer does, and the east one only at the hole, if at all.
  const BoxesProbe probe = wall_with_hole(17.0, 2.0);
  Roadmap map;
  map.build(kArena, probe);
  const std::vector<Vec3> sources = {{8.5, 5, 4}, {11.5, 5, 4}, {1.5, 9, 4}};
  map.partition(sources);
  const auto west = map.border_point(2);
  ASSERT_TRUE(west.has_value());
  EXPECT_LT(west->x(), 9.5);
  if (const auto east = map.border_point(1)) {
    EXPECT_GT(east->y(), 14.0) << east->transpose();
  }
  EXPECT_EQ(map.owner(map.cell_of({10.0, 5.0, 4.0})), -1);  // the wall is nobody's
  EXPECT_EQ(map.owner(map.cell_of({7.5, 5.0, 4.0})), 0);
}

TEST(Roadmap, APartitionIsTheSameWhateverWasAskedBeforeOnOtherSolids) {
  // The team's pursuers share the last answer; one asked on other solids must not be given it.
  const BoxesProbe low = wall_with_hole(4.0, 2.0), high = wall_with_hole(16.0, 2.0);
  const std::vector<Vec3> sources = {{8.0, 10, 4}, {12.0, 10, 4}, {3.0, 3, 3}};
  Roadmap a, b, fresh;
  a.build(kArena, low);
  b.build(kArena, high);
  fresh.build(kArena, high);
  fresh.partition(sources);
  std::vector<int> first(std::size_t(fresh.cells()));
  for (int c = 0; c < fresh.cells(); ++c) first[std::size_t(c)] = fresh.owner(c);
  a.partition(sources);
  b.partition(sources);
  int differ = 0;
  for (int c = 0; c < b.cells(); ++c) {
    EXPECT_EQ(b.owner(c), first[std::size_t(c)]);
    differ += a.owner(c) != b.owner(c);
  }
  EXPECT_GT(differ, 10);  // the two walls do share the cells out differently
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
