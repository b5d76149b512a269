#include "geometry/half_spaces.hpp"

#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace peg3d {
namespace {

TEST(HalfSpacesNearest, APointInsideStaysWhereItIs) {
  const std::vector<HalfSpace> h{{Vec3::UnitX(), 0.5}, {Vec3::UnitY(), 0.0}};
  const Vec3 m(0.4, -2.0, 7.0);
  EXPECT_EQ(nearest_within(m, h), m);
  EXPECT_EQ(nearest_within(m, {}), m);
}

TEST(HalfSpacesNearest, OnePlaneIsTheOrthogonalProjection) {
  const Vec3 n = Vec3(1, 1, 0).normalized();
  const std::vector<HalfSpace> h{{n, 0.25}};
  const Vec3 m(1, 0, 0.5);
  // m . n = 1 / sqrt(2): moved back along n by the excess.
  const Vec3 expected = m - (1 / std::sqrt(2.0) - 0.25) * n;
  EXPECT_LT((nearest_within(m, h) - expected).norm(), 1e-15);
}

TEST(HalfSpacesNearest, TwoPlanesMeetOnTheirCommonLine) {
  // Two trunks, one on each side (x and y), no approach allowed: what is left is the vertical.
  const std::vector<HalfSpace> wedge{{Vec3::UnitX(), 0.0}, {Vec3::UnitY(), 0.0}};
  EXPECT_LT((nearest_within(Vec3(1, 1, 0.3), wedge) - Vec3(0, 0, 0.3)).norm(), 1e-15);
  // With room left before each (offsets), the corner of the two planes, z kept.
  const std::vector<HalfSpace> room{{Vec3::UnitX(), 0.2}, {Vec3::UnitY(), 0.1}};
  EXPECT_LT((nearest_within(Vec3(1, 1, 0.3), room) - Vec3(0.2, 0.1, 0.3)).norm(), 1e-15);
  // One of the two binds only: the projection onto the other already lies inside both.
  EXPECT_LT((nearest_within(Vec3(1, -1, 0), room) - Vec3(0.2, -1, 0)).norm(), 1e-15);
}

TEST(HalfSpacesNearest, ThreePlanesMeetAtTheirVertex) {
  const std::vector<HalfSpace> corner{{Vec3::UnitX(), 0.1}, {Vec3::UnitY(), 0.2}, {Vec3::UnitZ(), 0.3}};
  EXPECT_LT((nearest_within(Vec3(1, 1, 1), corner) - Vec3(0.1, 0.2, 0.3)).norm(), 1e-15);
  // Opposite normals with zero offsets pin an axis; three of them leave only the origin.
  const std::vector<HalfSpace> pinned{{Vec3::UnitX(), 0.0}, {-Vec3::UnitX(), 0.0}, {Vec3::UnitY(), 0.0},
                                      {-Vec3::UnitY(), 0.0}, {Vec3::UnitZ(), 0.0}, {-Vec3::UnitZ(), 0.0}};
  EXPECT_EQ(nearest_within(Vec3(0.3, -0.2, 0.1), pinned), Vec3::Zero());
}

// Dykstra's alternating projections converge to the nearest point of an intersection of convex sets: the
// reference, by another method, for random cases.
Vec3 dykstra(const Vec3& m, const std::vector<HalfSpace>& h, int rounds) {
  Vec3 x = m;
  std::vector<Vec3> correction(h.size(), Vec3::Zero());
  for (int r = 0; r < rounds; ++r) {
    for (std::size_t i = 0; i < h.size(); ++i) {
      const Vec3 y = x + correction[i];
      const double excess = y.dot(h[i].normal) - h[i].offset;
      const Vec3 projected = excess > 0.0 ? Vec3(y - excess * h[i].normal) : y;
      correction[i] = y - projected;
      x = projected;
    }
  }
  return x;
}

TEST(HalfSpacesNearest, AgreesWithDykstrasProjectionsOnRandomCases) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> offset(0.0, 0.5);
  int bound = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<HalfSpace> h(1 + trial % 7);
    for (HalfSpace& s : h) {
      s.normal = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
      s.offset = trial % 3 == 0 ? 0.0 : offset(rng);
    }
    const Vec3 m(normal(rng), normal(rng), normal(rng));
    const Vec3 got = nearest_within(m, h);
    for (const HalfSpace& s : h) EXPECT_LE(got.dot(s.normal), s.offset + 1e-12) << "trial " << trial;
    EXPECT_NEAR((got - dykstra(m, h, 20000)).norm(), 0.0, 1e-7) << "trial " << trial;
    bound += got != m;
  }
  EXPECT_GT(bound, 300);  // most cases are projections, not m itself
}

}  // namespace
}  // namespace peg3d
