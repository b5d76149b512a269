#include "geometry/motion_cone.hpp"

#include <gtest/gtest.h>

#include "core/validation.hpp"
#include "geometry/angles.hpp"
#include "test_vectors.hpp"

namespace peg3d {
namespace {

TEST(MotionCone, PursuerHalfAngleForPaperSpeeds) {
  // vP = 1.1, vE = 1.0: alpha2* = asin(1/1.1) = 1.1410967 rad (65.38 deg).
  EXPECT_NEAR(pursuer_cone_half_angle(1.1, 1.0), std::asin(1.0 / 1.1), 1e-15);
  EXPECT_NEAR(pursuer_cone_half_angle(1.1, 1.0), 65.3800227 * kPi / 180, 1e-7);
  EXPECT_DOUBLE_EQ(pursuer_cone_half_angle(1.0, 1.0), kPi / 2);
  EXPECT_DOUBLE_EQ(pursuer_cone_half_angle(1.0, 2.0), kPi / 2);
}

TEST(MotionCone, ProjectedPursuerHeadingsLieInsideTheCone) {
  Rng rng(17);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 p = testing::random_point(rng), e = testing::random_point(rng);
    const Cone cone = pursuer_motion_cone(p, e, 1.1, 1.0);
    const Vec3 d = testing::random_unit(rng);
    const Vec3 q = cone.project(d);
    EXPECT_NEAR(q.norm(), 1.0, 1e-12);
    EXPECT_LE(angle_between(q, e - p), cone.half_angle + 1e-9);  // alpha2 <= alpha2*
    if (cone.contains(d)) {
      EXPECT_LT((q - d).norm(), 1e-12);  // inside headings are untouched
    } else {
      EXPECT_NEAR(angle_between(q, e - p), cone.half_angle, 1e-9);  // outside ones land on the surface
      EXPECT_LT(angle_between(q, d), angle_between(d, e - p));        // and move towards the axis
    }
  }
}

TEST(MotionCone, ProjectedEvaderHeadingsKeepAlpha1AtLeastRightAngle) {
  Rng rng(19);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 p = testing::random_point(rng), e = testing::random_point(rng);
    const Cone cone = evader_motion_cone(p, e);
    const Vec3 q = cone.project(testing::random_unit(rng));
    EXPECT_GE(angle_between(q, p - e), kPi / 2 - 1e-9);  // alpha1 = angle(EP, heading) >= pi/2
  }
}

TEST(MotionCone, HeadingOppositeToTheAxisProjectsDeterministically) {
  const Cone cone{Vec3::UnitX(), 0.5};
  const Vec3 q1 = cone.project(-Vec3::UnitX());
  const Vec3 q2 = cone.project(-Vec3::UnitX());
  EXPECT_EQ(q1, q2);
  EXPECT_NEAR(angle_between(q1, Vec3::UnitX()), 0.5, 1e-12);
}

TEST(MotionCone, MotionlessEvaderGivesAZeroWidthCone) { EXPECT_DOUBLE_EQ(pursuer_cone_half_angle(1.1, 0.0), 0.0); }

TEST(MotionCone, RejectsInvalidSpeeds) {
  EXPECT_THROW(pursuer_cone_half_angle(0.0, 1.0), InvalidParameter);
  EXPECT_THROW(pursuer_cone_half_angle(1.1, -1.0), InvalidParameter);
  EXPECT_THROW(pursuer_cone_half_angle(std::nan(""), 1.0), InvalidParameter);
}

}  // namespace
}  // namespace peg3d
