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

TEST(GeometryBoxIndex, AFanVisitsEveryBoxEachOfItsRaysEntersWithThatRaysBit) {
  // Rays from one origin (1 to 64 of them, some along an axis, some with a bound of 0 or no bound), in two
  // frames of different boxes, near the boxes and far from them: every box a ray enters within its bound is
  // visited once with that ray's bit, and no ray is reported for a box far off it. A caller that lowers each
  // ray's bound to its nearest entry ends with the first box of every ray, as a visit of every box finds it.
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> at(-2.0, 32.0), unit(-1.0, 1.0);
  const double step = 3 * 32.0 / 65000;
  long pairs = 0, extra = 0;
  for (const int n : {1, 5, 16, 17, 1000, int(BoxIndex::kMaxBoxes)}) {
    std::vector<Box> boxes = random_boxes(rng, n, 30.0);
    const std::vector<Box> second = random_boxes(rng, n, 30.0);
    boxes.insert(boxes.end(), second.begin(), second.end());
    const BoxIndex index(boxes, 2);
    for (int q = 0; q < 60; ++q) {
      const int frame = q % 2;
      const std::span<const Box> frame_boxes(boxes.data() + std::size_t(frame) * std::size_t(n), std::size_t(n));
      const Vec3 o = q % 10 == 9 ? Vec3(500.0, -300.0, 40.0) : Vec3(at(rng), at(rng), at(rng));
      const int rays = q % 4 == 0 ? BoxIndex::kFanRays : 1 + int(rng() % BoxIndex::kFanRays);
      std::vector<Vec3> d(static_cast<std::size_t>(rays));
      std::vector<double> bound(static_cast<std::size_t>(rays));
      for (int k = 0; k < rays; ++k) {
        Vec3 v(unit(rng), unit(rng), unit(rng));
        if (k % 9 == 0) v = Vec3(0, unit(rng) < 0 ? -1 : 1, 0);  // along an axis
        if (v.norm() < 1e-3) v = Vec3(1, 0, 0);
        d[std::size_t(k)] = v.normalized();
        bound[std::size_t(k)] = k % 11 == 3 ? 0.0 : k % 13 == 5 ? std::numeric_limits<double>::infinity() : k % 3 == 0 ? 4.0 : 60.0;
        if (q % 10 == 9) bound[std::size_t(k)] = std::numeric_limits<double>::infinity();
      }
      std::vector<std::uint64_t> found(std::size_t(n), 0);
      index.fan(frame, o, d, bound.data(), [&](int i, std::uint64_t bits) {
        ASSERT_EQ(found[std::size_t(i)], 0u) << "box " << i << " visited twice";
        ASSERT_NE(bits, 0u);
        found[std::size_t(i)] = bits;
      });
      for (int i = 0; i < n; ++i) {
        const Box& b = frame_boxes[std::size_t(i)];
        for (int k = 0; k < rays; ++k) {
          const Ray ray{o, d[std::size_t(k)]};
          const bool entered = ray_box(ray, b.lo, b.hi, bound[std::size_t(k)]).has_value();
          const bool visited = (found[std::size_t(i)] >> k) & 1;
          ASSERT_TRUE(!entered || visited) << "n " << n << " query " << q << ": ray " << k << " box " << i << " missed";
          pairs += entered, extra += visited && !entered;
          if (visited) {
            // In the cone of the box's bounding ball (widened by the steps the index rounds boxes out by and by
            // the float rounding of the coordinates), entered within the bound: the cone's angle may open by a
            // few float epsilons of the distance (1e-5 here).
            const Vec3 c = b.center() - o;
            const double r = 0.5 * b.size().norm() + 2 * step + 1e-5 * (1.0 + o.norm() + 32.0);
            if (c.norm() > r) {
              const double tolerance = 1e-5 * (1.0 + c.norm());
              ASSERT_GE(c.dot(ray.direction), std::sqrt(c.squaredNorm() - r * r) - tolerance)
                  << "n " << n << " query " << q << ": ray " << k << " box " << i << " far off";
              ASSERT_LE(c.norm() - r - tolerance, bound[std::size_t(k)]);
            }
          }
        }
      }
      // The first box of each ray, the bounds lowered as entries are found.
      std::vector<int> best(std::size_t(rays), -1);
      std::vector<double> best_t = bound;
      index.fan(frame, o, d, best_t.data(), [&](int i, std::uint64_t bits) {
        const Box& b = frame_boxes[std::size_t(i)];
        for (; bits != 0; bits &= bits - 1) {
          const std::size_t k = std::size_t(__builtin_ctzll(bits));
          const auto t = ray_box({o, d[k]}, b.lo, b.hi, best_t[k]);
          if (t && (*t < best_t[k] || (*t == best_t[k] && (best[k] < 0 || i < best[k])))) best[k] = i, best_t[k] = *t;
        }
      });
      for (int k = 0; k < rays; ++k) {
        int expected = -1;
        double expected_t = bound[std::size_t(k)];
        for (int i = 0; i < n; ++i) {
          const Box& b = frame_boxes[std::size_t(i)];
          const auto t = ray_box({o, d[std::size_t(k)]}, b.lo, b.hi, expected_t);
          if (t && (*t < expected_t || (*t == expected_t && (expected < 0 || i < expected)))) expected = i, expected_t = *t;
        }
        ASSERT_EQ(best[std::size_t(k)], expected) << "n " << n << " query " << q << " ray " << k;
        ASSERT_EQ(best_t[std::size_t(k)], expected_t);
      }
    }
  }
  std::printf("%ld ray-box entries, %ld more pairs visited\n", pairs, extra);
  EXPECT_GT(pairs, 5000);
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
