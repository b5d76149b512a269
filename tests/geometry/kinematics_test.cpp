#include "geometry/kinematics.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "core/validation.hpp"
#include "test_vectors.hpp"

namespace peg3d {
namespace {

const Box kArena{{0, 0, 0}, {35, 35, 20}};

TEST(Kinematics, MovesSpeedTimesDtAlongTheHeading) {
  // Eq. (1) with dt: theta = pi/2 and alpha = 0 is +x; theta = 0 is +z.
  KinematicState s{{10, 10, 10}, {0.0, kPi / 2}};
  KinematicState n = step(s, {}, 1.1, 0.1, kPi / 4, kArena);
  EXPECT_LT((n.position - Vec3(10.11, 10, 10)).norm(), 1e-12);
  s.heading = {0.3, 0.0};
  n = step(s, {}, 2.0, 0.5, kPi / 4, kArena);
  EXPECT_LT((n.position - Vec3(10, 10, 11)).norm(), 1e-12);
  s.heading = {kPi / 4, kPi / 4};
  n = step(s, {}, 1.0, 1.0, kPi / 4, kArena);
  EXPECT_LT((n.position - Vec3(10.5, 10.5, 10 + std::sqrt(0.5))).norm(), 1e-12);
}

TEST(Kinematics, AdvanceMovesAlongTheGivenHeadingAndSlidesAlongTheArena) {
  const Box box{Vec3::Zero(), Vec3(10, 10, 10)};
  const KinematicState s{Vec3(5, 5, 5), Heading{0.0, kPi / 2}};
  const KinematicState up = advance(s, Heading{0.0, 0.0}, 2.0, 0.5, box);  // straight up, 1 m
  EXPECT_NEAR((up.position - Vec3(5, 5, 6)).norm(), 0.0, 1e-12);
  EXPECT_EQ(up.heading.theta, 0.0);
  const KinematicState wall = advance({Vec3(9.9, 5, 5), s.heading}, Heading{kPi / 4, kPi / 2}, 1.0, 1.0, box);
  EXPECT_EQ(wall.position.x(), 10.0);  // clamped into the box: the motion along the wall remains
  EXPECT_NEAR(wall.position.y(), 5.0 + std::sqrt(0.5), 1e-12);
  // step() is steering followed by advance().
  const Steering u{0.3, -0.2};
  const KinematicState a = step(s, u, 1.0, 0.1, kPi / 4, box);
  const KinematicState b = advance(s, steer(s.heading, u, kPi / 4), 1.0, 0.1, box);
  EXPECT_EQ(a.position, b.position);
}

TEST(Kinematics, SteeringIsClampedToTheBound) {
  const Heading h = steer({0.0, kPi / 2}, {2.0, -3.0}, kPi / 4);
  EXPECT_DOUBLE_EQ(h.alpha, kPi / 4);
  EXPECT_DOUBLE_EQ(h.theta, kPi / 4);
  const Heading g = steer({0.0, kPi / 2}, {-0.1, 0.2}, kPi / 4);
  EXPECT_DOUBLE_EQ(g.alpha, -0.1);
  EXPECT_DOUBLE_EQ(g.theta, kPi / 2 + 0.2);
}

TEST(Kinematics, HeadingsStayValid) {
  Rng rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Heading h;
  for (int i = 0; i < 100000; ++i) {
    h = steer(h, {u(rng) * 2, u(rng) * 2}, kPi / 4);
    ASSERT_GT(h.alpha, -kPi);
    ASSERT_LE(h.alpha, kPi);
    ASSERT_GE(h.theta, 0.0);
    ASSERT_LE(h.theta, kPi);
  }
  EXPECT_DOUBLE_EQ(steer({3.0, 0.1}, {0.5, -0.5}, kPi / 4).alpha, 3.5 - 2 * kPi);  // wrapped
  EXPECT_DOUBLE_EQ(steer({3.0, 0.1}, {0.5, -0.5}, kPi / 4).theta, 0.0);            // not over the pole
}

TEST(Kinematics, PositionsRespectTheArenaBounds) {
  const Box inner = kArena.shrunk(0.25);
  KinematicState s{{34.7, 1.0, 19.7}, {0.0, kPi / 4}};  // heading +x and up, into the corner
  for (int i = 0; i < 50; ++i) {
    s = step(s, {}, 1.1, 0.1, kPi / 4, inner);
    ASSERT_TRUE(inner.contains(s.position));
  }
  EXPECT_DOUBLE_EQ(s.position.x(), 34.75);
  EXPECT_DOUBLE_EQ(s.position.z(), 19.75);
}

TEST(Kinematics, PerSecondReadingScalesTheBoundByDt) {
  SteeringConfig c{kPi / 4, SteeringReading::kPerSecond};
  EXPECT_DOUBLE_EQ(c.step_bound(0.1), kPi / 40);
  c.reading = SteeringReading::kPerStep;
  EXPECT_DOUBLE_EQ(c.step_bound(0.1), kPi / 4);
}

TEST(Kinematics, DirectionAndHeadingRoundTrip) {
  Rng rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 d = testing::random_unit(rng);
    EXPECT_LT((direction(heading_of(d)) - d).norm(), 1e-12);
  }
}

TEST(Kinematics, RejectsInvalidSteeringBound) {
  for (double bad : {0.0, -0.1, 4.0, std::nan("")}) {
    try {
      SteeringConfig{bad, SteeringReading::kPerStep}.validate();
      ADD_FAILURE() << bad;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.parameter(), "steering.max_turn");
    }
  }
}

}  // namespace
}  // namespace peg3d

namespace peg3d {
namespace {

TEST(AngleErrors, SteeringByTheErrorsPointsAtTheDirection) {
  Rng rng(23);
  for (int i = 0; i < 1000; ++i) {
    const Heading h = heading_of(testing::random_unit(rng));
    const Vec3 d = testing::random_unit(rng);
    const AngleErrors e = angle_errors(h, d);
    ASSERT_LE(std::abs(e.azimuth), kPi);
    ASSERT_LE(std::abs(e.elevation), kPi);
    const Heading aimed = steer(h, {e.azimuth, e.elevation}, kPi);
    EXPECT_LT((direction(aimed) - d).norm(), 1e-9);
  }
}

TEST(AngleErrors, SignsFollowTheHeadingAngles) {
  const Heading level_x{0.0, kPi / 2};
  EXPECT_NEAR(angle_errors(level_x, Vec3(1, 1, 0)).azimuth, kPi / 4, 1e-15);   // to the left: +alpha
  EXPECT_NEAR(angle_errors(level_x, Vec3(1, 0, 1)).elevation, -kPi / 4, 1e-15);  // above: theta decreases
  EXPECT_NEAR(std::abs(angle_errors(level_x, Vec3(-1, 0, 0)).azimuth), kPi, 1e-15);
}

}  // namespace
}  // namespace peg3d
