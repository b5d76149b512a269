// The box index (geometry/box_index.hpp) against a visit of every box: the same overlaps and the same nearest
// box, on random boxes and queries (far from the origin too), duplicates, sizes that leave clusters partly empty,
// the most boxes an index holds, an index of one box, and boxes that move from frame to frame.
#include "geometry/box_index.hpp"
#include "geometry/ray.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <span>
#include <vector>

namespace peg3d {
namespace {

double box_distance(const Box& b, const Vec3& p) { return (p - b.clamp(p)).norm(); }

std::vector<Box> random_boxes(std::mt19937_64& rng, int n, double spread, const Vec3& offset = Vec3::Zero()) {
  std::uniform_real_distribution<double> at(0.0, spread), size(0.01, 2.0);
  std::vector<Box> boxes;
  for (int i = 0; i < n; ++i) {
    const Vec3 lo = offset + Vec3(at(rng), at(rng), at(rng));
    boxes.push_back({lo, lo + Vec3(size(rng), size(rng), size(rng))});
  }
  return boxes;
}

bool meets(const Box& b, const Box& q) { return (b.lo.array() <= q.hi.array()).all() && (q.lo.array() <= b.hi.array()).all(); }

// Checks what the index reports meeting q in `frame` (whose boxes are `boxes`) against a visit of every box: none
// missed, none reported twice, and every one within 3 steps of the query (bounds are kept in steps of a 65000th
// of the index's extent, `extent` m or less, rounded outwards by a step: a box that misses by a few steps may be
// reported). `met`, when given, counts the queries that meet a box.
::testing::AssertionResult overlaps_as_a_visit(const BoxIndex& index, int frame, std::span<const Box> boxes,
                                               const Box& q, double extent, int* met = nullptr,
                                               std::size_t* extra = nullptr) {
  std::vector<int> found, expected;
  index.overlapping(frame, q, [&](int i) { found.push_back(i); });
  for (int i = 0; i < int(boxes.size()); ++i) {
    if (meets(boxes[std::size_t(i)], q)) expected.push_back(i);
  }
  if (met) *met += !expected.empty();
  if (extra) *extra = found.size() - std::min(found.size(), expected.size());
  std::sort(found.begin(), found.end());
  if (std::adjacent_find(found.begin(), found.end()) != found.end()) {
    return ::testing::AssertionFailure() << "a box reported twice";
  }
  if (!std::includes(found.begin(), found.end(), expected.begin(), expected.end())) {
    return ::testing::AssertionFailure() << "a box that meets the query is missing";
  }
  const double step = 3 * extent / 65000;
  for (const int i : found) {
    const Box& b = boxes[std::size_t(i)];
    if (!meets({b.lo.array() - step, b.hi.array() + step}, q)) {
      return ::testing::AssertionFailure() << "box " << i << " is far from the query";
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(GeometryBoxIndex, OverlapsAreThoseOfAVisitOfEveryBox) {
  std::mt19937_64 rng(7);
  for (const int n : {1, 3, 17, 33, 1000, int(BoxIndex::kMaxBoxes)}) {
    // Away from the origin too: the index keeps coordinates relative to its boxes' corner.
    const Vec3 offset = n == 33 ? Vec3(5000, -3000, 200) : Vec3::Zero();
    std::vector<Box> boxes = random_boxes(rng, n, 30.0, offset);
    if (n == 1000) std::fill(boxes.begin(), boxes.begin() + 200, boxes[0]);  // many copies of one box
    const BoxIndex index(boxes);
    EXPECT_EQ(index.size(), std::size_t(n));
    // A box that misses by a few steps may be reported (about 1.5 mm here), never one dropped.
    for (const Box& q : random_boxes(rng, 300, 32.0, offset)) {
      EXPECT_TRUE(overlaps_as_a_visit(index, 0, boxes, q, 32.0));
    }
  }
}

TEST(GeometryBoxIndex, IndexesOfOneClusterOverlapAsAVisitOfEveryBox) {
  // Up to 16 boxes make one cluster. Queries around the boxes, so that many meet some and many meet none (in
  // the test above, boxes spread over 30 m rarely meet a query when there are few).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> shift(-1.0, 1.0), half(0.05, 1.0);
  for (const int n : {1, 3, 16}) {
    const std::vector<Box> boxes = random_boxes(rng, n, 30.0);
    const BoxIndex index(boxes);
    int met = 0;
    for (int j = 0; j < 200; ++j) {
      const Vec3 c = boxes[std::size_t(j % n)].center() + Vec3(shift(rng), shift(rng), shift(rng));
      const Vec3 h(half(rng), half(rng), half(rng));
      std::size_t extra = 0;
      EXPECT_TRUE(overlaps_as_a_visit(index, 0, boxes, {c - h, c + h}, 32.0, &met, &extra));
      EXPECT_LE(extra, 1u) << "at most a box that misses by a step";
    }
    EXPECT_GT(met, 20) << n << " boxes: the queries must meet boxes to test anything";
    EXPECT_LT(met, 180) << n << " boxes: and miss some";
  }
}

TEST(GeometryBoxIndex, NearestFindsTheNearestBoxWithinTheBoundAsAVisitOfEveryBox) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> at(-2.0, 32.0);
  for (const int n : {1, 5, 16, 17, 1000, int(BoxIndex::kMaxBoxes)}) {
    const std::vector<Box> boxes = random_boxes(rng, n, 30.0);
    const BoxIndex index(boxes);
    for (int q = 0; q < 500; ++q) {
      const Vec3 p(at(rng), at(rng), at(rng));
      const double cap = q % 3 == 0 ? 1.0 : 50.0;
      // The callback keeps the nearest, the lower index on a tie, as the game's queries do.
      int best = -1, visits = 0;
      double best_d = cap;
      index.nearest(p, cap, [&](int i) {
        ++visits;
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
      EXPECT_LE(visits, 64) << "nearer boxes first: the bound prunes the rest";
    }
  }
}

TEST(GeometryBoxIndex, AlongVisitsEveryBoxTheRayEntersAndFindsTheFirstAsAVisitOfEveryBox) {
  // Every box the ray enters within the bound is visited (none twice, none far off the ray), in two frames of
  // different boxes; and a caller that returns the nearest entry so far as the bound ends with the first box
  // the ray enters, as a visit of every box finds it, after few visits.
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> at(-2.0, 32.0), unit(-1.0, 1.0);
  for (const int n : {1, 5, 16, 17, 1000, int(BoxIndex::kMaxBoxes)}) {
    std::vector<Box> boxes = random_boxes(rng, n, 30.0);
    const std::vector<Box> second = random_boxes(rng, n, 30.0);
    boxes.insert(boxes.end(), second.begin(), second.end());
    const BoxIndex index(boxes, 2);
    long visits_total = 0;
    for (int q = 0; q < 400; ++q) {
      const int frame = q % 2;
      const std::span<const Box> frame_boxes(boxes.data() + std::size_t(frame) * std::size_t(n), std::size_t(n));
      const Vec3 o(at(rng), at(rng), at(rng));
      Vec3 d(unit(rng), unit(rng), unit(rng));
      if (q % 7 == 0) d = Vec3(0, 0, unit(rng) < 0 ? -1 : 1);  // along an axis: the slabs of the others are parallel
      if (d.norm() < 1e-3) continue;
      d.normalize();
      const double range = q % 3 == 0 ? 4.0 : 60.0;
      std::vector<int> found;
      index.along(frame, o, d, range, [&](int i) {
        found.push_back(i);
        return range;
      });
      std::sort(found.begin(), found.end());
      ASSERT_EQ(std::adjacent_find(found.begin(), found.end()), found.end()) << "a box visited twice";
      const double step = 3 * 32.0 / 65000;
      for (int i = 0; i < n; ++i) {
        const Box& b = frame_boxes[std::size_t(i)];
        const bool entered = ray_box({o, d}, b.lo, b.hi, range).has_value();
        const bool visited = std::binary_search(found.begin(), found.end(), i);
        if (entered) {
          ASSERT_TRUE(visited) << "n " << n << " query " << q << ": box " << i << " missed";
        }
        if (visited) {
          ASSERT_TRUE(ray_box({o, d}, b.lo.array() - step, b.hi.array() + step, range + step)) << "box " << i << " far off";
        }
      }
      // The first box entered.
      int best = -1, visits = 0;
      double best_t = range;
      index.along(frame, o, d, range, [&](int i) {
        ++visits;
        const Box& b = frame_boxes[std::size_t(i)];
        const auto t = ray_box({o, d}, b.lo, b.hi, range);
        if (t && (*t < best_t || (*t == best_t && (best < 0 || i < best)))) best = i, best_t = *t;
        return best_t;
      });
      int expected = -1;
      double expected_t = range;
      for (int i = 0; i < n; ++i) {
        const Box& b = frame_boxes[std::size_t(i)];
        const auto t = ray_box({o, d}, b.lo, b.hi, range);
        if (t && (*t < expected_t || (*t == expected_t && (expected < 0 || i < expected)))) expected = i, expected_t = *t;
      }
      EXPECT_EQ(best, expected) << "n " << n << " query " << q;
      EXPECT_EQ(best_t, expected_t);
      visits_total += visits;
    }
    EXPECT_LE(visits_total / 400, 64) << "n " << n << ": earlier boxes first, the bound prunes the rest";
  }
}

TEST(GeometryBoxIndex, EachFrameIsAnsweredFromItsOwnBoxes) {
  // Boxes that move from frame to frame (as a mover's bounds do over a window's blocks), some far: a query of a
  // frame reports what a visit of that frame's boxes does, never a box only another frame has near.
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> at(-2.0, 32.0), step(-3.0, 3.0);
  constexpr int kFrames = 4, kBoxes = 500;
  std::vector<Box> boxes = random_boxes(rng, kBoxes, 30.0);
  for (int f = 1; f < kFrames; ++f) {
    for (int i = 0; i < kBoxes; ++i) {
      const Box& b = boxes[std::size_t((f - 1) * kBoxes + i)];
      const Vec3 d = i % 50 == 0 ? Vec3(12.0, 0.0, 0.0) : Vec3(step(rng), step(rng), step(rng));
      boxes.push_back({b.lo + d, b.hi + d});
    }
  }
  const BoxIndex index(boxes, kFrames);
  EXPECT_EQ(index.size(), std::size_t(kBoxes));
  for (int q = 0; q < 2000; ++q) {
    const int f = q % kFrames;
    const std::span<const Box> frame(boxes.data() + std::size_t(f) * kBoxes, kBoxes);
    const Vec3 p(at(rng), at(rng), at(rng));
    int best = -1;
    double best_d = 3.0;
    index.nearest(f, p, best_d, [&](int i) {
      const double d = box_distance(frame[std::size_t(i)], p);
      if (d < best_d || (best >= 0 && d == best_d && i < best)) best = i, best_d = d;
      return best_d;
    });
    int expected = -1;
    double expected_d = 3.0;
    for (int i = 0; i < kBoxes; ++i) {
      const double d = box_distance(frame[std::size_t(i)], p);
      if (d < expected_d) expected = i, expected_d = d;
    }
    ASSERT_EQ(best, expected) << "query " << q << " of frame " << f;
    ASSERT_TRUE(overlaps_as_a_visit(index, f, frame, {p, p + Vec3(1.0, 0.5, 2.0)}, 50.0)) << "query " << q;
  }
}

TEST(GeometryBoxIndex, AnEmptyIndexVisitsNothing) {
  const BoxIndex index;
  int visits = 0;
  index.overlapping({Vec3::Zero(), Vec3::Ones()}, [&](int) { ++visits; });
  index.nearest(Vec3::Zero(), 10.0, [&](int) { ++visits; return 10.0; });
  EXPECT_EQ(visits, 0);
}

}  // namespace
}  // namespace peg3d
