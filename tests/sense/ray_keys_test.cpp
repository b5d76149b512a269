// A scan's rays traced together (sense/ray_keys.hpp) against OctoMap's own computeRayKeys, ray by ray: the same keys
// in the same order, one ray at a time and in vector lanes, for batches of any size, at several resolutions, from
// random points and from cells' corners and centres (where the traversal's ties between axes fall), along the
// axes and diagonals (where directions have zero components) and in random directions, for rays shorter than a
// cell and ends beyond the keys' range.
#include "sense/ray_keys.hpp"

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/random.hpp"

namespace peg3d::sense {
namespace {

void expect_octomaps_keys(RayLanes lanes) {
  for (const double resolution : {0.25, 0.1, 0.4, 1.0}) {
    SCOPED_TRACE(resolution);
    const octomap::OcTree tree(resolution);
    Rng rng(std::uint64_t(resolution * 1000) + 3);
    std::vector<std::uint64_t> keys;
    std::vector<RayKeySpan> spans;
    long long rays = 0, cells = 0, ties = 0;
    for (int scan = 0; scan < 300; ++scan) {
      octomap::point3d origin(float(uniform(rng, -20, 20)), float(uniform(rng, -20, 20)), float(uniform(rng, -5, 5)));
      if (scan % 3 == 1) {  // a cell's corner
        for (unsigned i = 0; i < 3; ++i) origin(i) = float(std::round(origin(i) / resolution) * resolution);
      } else if (scan % 3 == 2) {  // a cell's centre
        for (unsigned i = 0; i < 3; ++i) origin(i) = float((std::floor(origin(i) / resolution) + 0.5) * resolution);
      }
      const int n = 1 + scan % 23;  // batches that fill no, one or several groups of lanes
      std::vector<octomap::point3d> ends;
      for (int k = 0; k < n; ++k) {
        octomap::point3d d;
        if (k % 3 == 0) {  // an axis or a diagonal: -1, 0 or 1 on each
          do d = octomap::point3d(float(int(rng() % 3) - 1), float(int(rng() % 3) - 1), float(int(rng() % 3) - 1));
          while (d.norm() == 0.0);
        } else {
          d = octomap::point3d(float(uniform(rng, -1, 1)), float(uniform(rng, -1, 1)), float(uniform(rng, -1, 1)));
        }
        d.normalize();
        const double length = k % 7 == 3 ? uniform(rng, 0.0, resolution) : k % 11 == 5 ? 1e5 : uniform(rng, 0.0, 15.0);
        ends.push_back(origin + d * float(length));
      }
      const std::size_t used = trace_rays(tree, origin, ends, keys, spans, lanes);
      ASSERT_EQ(spans.size(), ends.size());
      octomap::KeyRay expected;
      for (std::size_t k = 0; k < ends.size(); ++k) {
        ++rays;
        const bool traced = tree.computeRayKeys(origin, ends[k], expected);
        const RayKeySpan& span = spans[k];
        ASSERT_EQ(span.count, traced ? expected.size() : 0) << "ray " << k << " of scan " << scan;
        std::size_t j = 0;
        for (auto it = expected.begin(); it != expected.end(); ++it, ++j) {
          const std::size_t at = span.offset + j * span.stride;
          ASSERT_LT(at, used);
          const std::uint64_t word = keys[at];
          ASSERT_TRUE(packed_key(word, 0) == (*it)[0] && packed_key(word, 1) == (*it)[1] && packed_key(word, 2) == (*it)[2])
              << "ray " << k << " of scan " << scan << ", cell " << j;
          ++cells;
        }
        for (unsigned i = 0; i < 3; ++i) ties += std::fabs((ends[k] - origin)(i)) == std::fabs((ends[k] - origin)((i + 1) % 3));
      }
    }
    std::printf("at %.2f m: %lld rays, %lld cells, %lld rays with two equal components\n", resolution, rays, cells, ties);
    EXPECT_GT(double(cells), 3.0 / resolution * double(rays));  // a ray of 7.5 m on average crosses more
  }
}

TEST(RayKeys, RaysOneAtATimeMeetOctomapsKeys) { expect_octomaps_keys(RayLanes::kScalar); }

// Where computeRayKeys gives nothing (an origin beyond the keys' range, an end that is not a number or infinite),
// neither way of tracing gives a key, in every lane of a group.
TEST(RayKeys, RaysOctomapCannotTraceGiveNoKeys) {
  const octomap::OcTree tree(0.25);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::vector<octomap::point3d> odd{octomap::point3d(nan, 1, 1), octomap::point3d(1, inf, 1), octomap::point3d(1, 1, -inf),
                                          octomap::point3d(9000, 0, 0), octomap::point3d(2, 1, 0), octomap::point3d(0, 3, 1),
                                          octomap::point3d(nan, nan, nan), octomap::point3d(-3, -2, 1)};
  for (const octomap::point3d& origin : {octomap::point3d(0.1f, 0.2f, 0.3f), octomap::point3d(9000, 0, 0), octomap::point3d(0, -1e6f, 0)}) {
    for (const RayLanes lanes : {RayLanes::kScalar, RayLanes::kBest}) {
      std::vector<std::uint64_t> keys;
      std::vector<RayKeySpan> spans;
      trace_rays(tree, origin, odd, keys, spans, lanes);
      octomap::KeyRay expected;
      for (std::size_t k = 0; k < odd.size(); ++k) {
        const bool traced = tree.computeRayKeys(origin, odd[k], expected);
        EXPECT_EQ(spans[k].count, traced ? expected.size() : 0) << "ray " << k << " from " << origin;
        if (std::isfinite(odd[k].x() + odd[k].y() + odd[k].z()) && std::fabs(odd[k].x()) < 100 && std::fabs(origin.y()) < 100 &&
            origin.x() < 100) {
          EXPECT_TRUE(traced) << "ray " << k;  // the ordinary rays among them are traced
        } else {
          EXPECT_EQ(spans[k].count, 0u) << "ray " << k << " from " << origin;
        }
      }
    }
  }
}

// Where the processor has no AVX2, asking for vector lanes is refused instead of running instructions it lacks.
TEST(RayKeys, RaysInVectorLanesMeetOctomapsKeys) {
  if (!vector_lanes_available()) {
    const octomap::OcTree tree(0.25);
    std::vector<std::uint64_t> keys;
    std::vector<RayKeySpan> spans;
    const std::vector<octomap::point3d> ends{octomap::point3d(3, 2, 1)};
    EXPECT_THROW(trace_rays(tree, octomap::point3d(0, 0, 0), ends, keys, spans, RayLanes::kVector), std::invalid_argument);
    GTEST_SKIP() << "this processor has no AVX2: vector lanes are refused";
  }
  expect_octomaps_keys(RayLanes::kVector);
}

}  // namespace
}  // namespace peg3d::sense
