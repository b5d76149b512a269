#include "geometry/apollonius.hpp"

#include <gtest/gtest.h>

#include "core/validation.hpp"
#include "test_vectors.hpp"

namespace peg3d {
namespace {

using testing::random_point;
using testing::random_unit;

class ApolloniusRatio : public ::testing::TestWithParam<double> {};

TEST_P(ApolloniusRatio, PointsOnTheSphereHaveDistanceRatioA) {
  const double a = GetParam();
  Rng rng(derive_seed(1, {static_cast<std::uint64_t>(a * 1000)}));
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p = random_point(rng), e = random_point(rng);
    const ApolloniusSurface s(p, e, a);
    ASSERT_FALSE(s.is_plane());
    const Vec3 c = s.sphere().center + s.sphere().radius * random_unit(rng);
    EXPECT_NEAR((c - e).norm() / (c - p).norm(), a, 1e-9);
    EXPECT_NEAR(s.dominance(c) / (c - e).norm(), 0.0, 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(BelowAndAboveOne, ApolloniusRatio, ::testing::Values(0.2, 0.5, 1.0 / 1.1, 0.99, 1.01, 1.5, 3.0));

TEST(Apollonius, UnitRatioIsTheEquidistantBisectingPlane) {
  Rng rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p = random_point(rng), e = random_point(rng);
    const ApolloniusSurface s(p, e, 1.0);
    ASSERT_TRUE(s.is_plane());
    Vec3 c = random_point(rng);
    c -= s.plane().signed_distance(c) * s.plane().normal;  // project onto the plane
    EXPECT_NEAR((c - e).norm() - (c - p).norm(), 0.0, 1e-9);
    EXPECT_GT(s.plane().signed_distance(e), 0.0);  // normal points from P towards E
  }
}

// Paper Fig. 2: P = (10,10,10), E = (-10,-10,10). Eq. (3) by hand:
//   a = 1/2:   center = (E - P/4) / (3/4) = (-50/3, -50/3, 10), radius = (1/2)/(3/4) |PE| = (2/3) 20 sqrt(2).
//   a = 1/1.1: center = (1.21 E - P) / 0.21 = (-22.1/0.21, -22.1/0.21, 10), radius = (1.1/0.21) 20 sqrt(2).
//   a = 2:     center = (E - 4P) / (-3) = (50/3, 50/3, 10), radius = (2/3) 20 sqrt(2) (encloses P).
TEST(Apollonius, PaperFigure2Example) {
  const Vec3 p(10, 10, 10), e(-10, -10, 10);
  const double pe = 20.0 * std::sqrt(2.0);
  struct Case { double a; Vec3 center; double radius; };
  for (const Case& c : {Case{0.5, {-50.0 / 3, -50.0 / 3, 10}, 2.0 / 3 * pe},
                        Case{1.0 / 1.1, {-22.1 / 0.21, -22.1 / 0.21, 10}, 1.1 / 0.21 * pe},
                        Case{2.0, {50.0 / 3, 50.0 / 3, 10}, 2.0 / 3 * pe}}) {
    const ApolloniusSurface s(p, e, c.a);
    EXPECT_LT((s.sphere().center - c.center).norm(), 1e-9) << "a = " << c.a;
    EXPECT_NEAR(s.sphere().radius, c.radius, 1e-9) << "a = " << c.a;
  }
  const ApolloniusSurface unit(p, e, 1.0);
  EXPECT_LT((unit.plane().point - Vec3(0, 0, 10)).norm(), 1e-12);
}

TEST(Apollonius, DominanceRegions) {
  const Vec3 p(10, 10, 10), e(-10, -10, 10);
  const ApolloniusSurface slow(p, e, 0.5);
  EXPECT_EQ(slow.first_arrival(e), FirstArrival::kEvader);
  EXPECT_EQ(slow.first_arrival(p), FirstArrival::kPursuer);
  EXPECT_EQ(slow.first_arrival(slow.sphere().center), FirstArrival::kEvader);  // a < 1: the ball is the evader's
  const Vec3 on = slow.sphere().center + slow.sphere().radius * Vec3::UnitZ();
  EXPECT_EQ(slow.first_arrival(on, 1e-9), FirstArrival::kTie);
  const ApolloniusSurface fast(p, e, 2.0);
  EXPECT_EQ(fast.first_arrival(fast.sphere().center), FirstArrival::kPursuer);  // a > 1: the ball is the pursuer's
  EXPECT_EQ(fast.first_arrival(Vec3(-100, -100, 10)), FirstArrival::kEvader);
}

TEST(Apollonius, RejectsInvalidRatio) {
  const Vec3 p(0, 0, 0), e(1, 0, 0);
  EXPECT_THROW(ApolloniusSurface(p, e, 0.0), InvalidParameter);
  EXPECT_THROW(ApolloniusSurface(p, e, -1.0), InvalidParameter);
  EXPECT_THROW(ApolloniusSurface(p, e, std::nan("")), InvalidParameter);
  EXPECT_THROW(ApolloniusSurface(Vec3(std::nan(""), 0, 0), e, 0.5), InvalidParameter);
}

TEST(Interception, StraightAwayRunIsCaughtAtTheAnalyticDistance) {
  // P at 0, E at D on +x running along +x: D + s = s / a  =>  s = a D / (1 - a).
  const double a = 1.0 / 1.1, d = 12.0;
  const auto x = interception_point(Vec3::Zero(), Vec3(d, 0, 0), Vec3::UnitX(), a);
  ASSERT_TRUE(x.has_value());
  EXPECT_NEAR(x->x(), d + a * d / (1 - a), 1e-9);
}

TEST(Interception, PointLiesOnTheApolloniusSphereAlongTheEvadersRay) {
  Rng rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p = random_point(rng), e = random_point(rng), dir = random_unit(rng);
    const double a = 0.7;
    const auto x = interception_point(p, e, dir, a);
    ASSERT_TRUE(x.has_value());
    EXPECT_NEAR((*x - e).norm() / (*x - p).norm(), a, 1e-9);
    EXPECT_NEAR((*x - e).normalized().dot(dir), 1.0, 1e-9);
  }
}

TEST(Interception, FasterEvaderRunningAwayIsNeverCaught) {
  EXPECT_FALSE(interception_point(Vec3::Zero(), Vec3(5, 0, 0), Vec3::UnitX(), 1.5).has_value());
  EXPECT_FALSE(interception_point(Vec3::Zero(), Vec3(5, 0, 0), Vec3::UnitX(), 1.0).has_value());
  // ...but one running towards the pursuer is.
  const auto x = interception_point(Vec3::Zero(), Vec3(5, 0, 0), -Vec3::UnitX(), 1.0);
  ASSERT_TRUE(x.has_value());
  EXPECT_NEAR(x->x(), 2.5, 1e-12);
}

}  // namespace
}  // namespace peg3d
