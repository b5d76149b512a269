// The box tree (geometry/box_tree.hpp) against a visit of every box: the same overlaps and the same nearest box,
// on random boxes and queries, duplicates and a tree of one box included.
#include "geometry/box_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

namespace peg3d {
namespace {

double box_distance(const Box& b, const Vec3& p) { return (p - b.clamp(p)).norm(); }

std::vector<Box> random_boxes(std::mt19937_64& rng, int n, double spread) {
  std::uniform_real_distribution<double> at(0.0, spread), size(0.01, 2.0);
  std::vector<Box> boxes;
  for (int i = 0; i < n; ++i) {
    const Vec3 lo(at(rng), at(rng), at(rng));
    boxes.push_back({lo, lo + Vec3(size(rng), size(rng), size(rng))});
  }
  return boxes;
}

TEST(GeometryBoxTree, OverlapsAreExactlyThoseOfAVisitOfEveryBox) {
  std::mt19937_64 rng(7);
  for (const int n : {1, 3, 17, 1000}) {
    std::vector<Box> boxes = random_boxes(rng, n, 30.0);
    if (n == 1000) std::fill(boxes.begin(), boxes.begin() + 200, boxes[0]);  // many copies of one box
    const BoxTree tree(boxes);
    for (const Box& q : random_boxes(rng, 300, 32.0)) {
      std::vector<int> found, expected;
      tree.overlapping(q, [&](int i) { found.push_back(i); });
      for (int i = 0; i < n; ++i) {
        const Box& b = boxes[std::size_t(i)];
        if ((b.lo.array() <= q.hi.array()).all() && (q.lo.array() <= b.hi.array()).all()) expected.push_back(i);
      }
      std::sort(found.begin(), found.end());
      // The tree's float bounds may add a box that misses by a rounding, never drop one.
      EXPECT_TRUE(std::includes(found.begin(), found.end(), expected.begin(), expected.end()));
      EXPECT_LE(found.size(), expected.size() + 2);
    }
  }
}

TEST(GeometryBoxTree, NearestFindsTheNearestBoxWithinTheBoundAsAVisitOfEveryBox) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> at(-2.0, 32.0);
  for (const int n : {1, 5, 1000}) {
    const std::vector<Box> boxes = random_boxes(rng, n, 30.0);
    const BoxTree tree(boxes);
    for (int q = 0; q < 500; ++q) {
      const Vec3 p(at(rng), at(rng), at(rng));
      const double cap = q % 3 == 0 ? 1.0 : 50.0;
      // The callback keeps the nearest, the lower index on a tie, as the game's queries do.
      int best = -1;
      double best_d = cap;
      tree.nearest(p, cap, [&](int i) {
        const double d = box_distance(boxes[std::size_t(i)], p);
        if (d < best_d || (best >= 0 && d == best_d && i < best)) best = i, best_d = d;
        return best_d;
      });
      int expected = -1;
      double expected_d = cap;
      for (int i = 0; i < n; ++i) {
        const double d = box_distance(boxes[std::size_t(i)], p);
        if (d < expected_d) expected = i, expected_d = d;
      }
      EXPECT_EQ(best, expected) << "query " << q;
      EXPECT_EQ(best_d, expected_d);
    }
  }
}

TEST(GeometryBoxTree, AnEmptyTreeVisitsNothing) {
  const BoxTree tree;
  int visits = 0;
  tree.overlapping({Vec3::Zero(), Vec3::Ones()}, [&](int) { ++visits; });
  tree.nearest(Vec3::Zero(), 10.0, [&](int) { ++visits; return 10.0; });
  EXPECT_EQ(visits, 0);
}

}  // namespace
}  // namespace peg3d
