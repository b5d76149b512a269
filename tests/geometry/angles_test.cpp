// wrap_angle (geometry/angles.hpp): its fast path gives std::remainder's bits exactly.
#include "geometry/angles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace peg3d {
namespace {

// What wrap_angle is defined as: the IEEE remainder by 2 pi, with -pi read as pi.
double reference_wrap(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a == -kPi ? kPi : a;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(WrapAngle, GivesTheRemaindersBitsEverywhere) {
  std::vector<double> values;
  // The edges of the fast path and of the rounding of the quotient, and the values next to them.
  for (const double edge : {0.0, kPi, 2.0 * kPi, 3.0 * kPi, 9.0, 4.0 * kPi, 1e-300, 1e300}) {
    for (const double sign : {1.0, -1.0}) {
      double v = sign * edge;
      values.push_back(v);
      for (int k = 0; k < 4; ++k) {
        values.push_back(std::nextafter(v, 1e308));
        values.push_back(std::nextafter(v, -1e308));
        v = std::nextafter(v, 1e308);
      }
    }
  }
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> near(-20.0, 20.0), far(-1e6, 1e6);
  for (int i = 0; i < 1000000; ++i) values.push_back(near(rng));
  for (int i = 0; i < 10000; ++i) values.push_back(far(rng));
  // Sums of two wrapped angles, the way steering and angle errors make them.
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < 100000; ++i) values.push_back(angle(rng) - angle(rng));
  for (const double v : values) ASSERT_TRUE(same_bits(wrap_angle(v), reference_wrap(v))) << v;
}

TEST(WrapAngle, StaysInTheHalfOpenInterval) {
  EXPECT_EQ(wrap_angle(-kPi), kPi);
  EXPECT_EQ(wrap_angle(kPi), kPi);
  EXPECT_EQ(wrap_angle(3.0 * kPi / 2.0), -kPi / 2.0);
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::quiet_NaN())));
}

TEST(RoughCos, StaysWithinItsBoundOverTheHalfTurn) {
  double worst = 0.0;
  for (int i = 0; i <= 1000000; ++i) {
    const double x = kPi * i / 1000000.0;
    worst = std::max(worst, std::abs(rough_cos(x) - std::cos(x)));
  }
  EXPECT_LT(worst, 1e-11);
}

TEST(ClimbLimit, AVectorsAnswerIsItsPolarAnglesEverywhere) {
  // The cosine shortcut of within_climb_limit(Vec3) against the polar angle, at random and at the limit.
  std::mt19937_64 rng(8);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> margin(0.0, 1.5), offset_exp(-17.0, -1.0), azimuth(-kPi, kPi);
  int near_limit = 0;
  for (int i = 0; i < 400000; ++i) {
    const double m = i % 50 == 0 ? 0.0 : margin(rng);
    Vec3 d(gauss(rng), gauss(rng), gauss(rng));
    if (i % 2 == 0) {
      const double pole = i % 4 == 0 ? m : kPi - m;
      const double theta = pole + (i % 8 < 4 ? 1.0 : -1.0) * std::pow(10.0, offset_exp(rng));
      d = direction(Heading{azimuth(rng), theta}) * std::exp(gauss(rng));
      ++near_limit;
    }
    ASSERT_EQ(within_climb_limit(d, m), within_climb_limit(heading_of(d).theta, m)) << d.transpose() << ", " << m;
  }
  EXPECT_GT(near_limit, 100000);
}

}  // namespace
TEST(ClimbLimit, KeepsThePolarAngleWithinTheMarginOfEitherPole) {
  const double margin = kPi / 3;  // 30 degrees of climb or dive
  EXPECT_TRUE(within_climb_limit(kPi / 2, margin));
  EXPECT_TRUE(within_climb_limit(margin, margin));  // the edges belong to the band
  EXPECT_TRUE(within_climb_limit(kPi - margin, margin));
  EXPECT_FALSE(within_climb_limit(margin - 1e-9, margin));
  EXPECT_FALSE(within_climb_limit(kPi - margin + 1e-9, margin));
  EXPECT_TRUE(within_climb_limit(Vec3(1, 0, 0.5), margin));   // 26.6 degrees up
  EXPECT_FALSE(within_climb_limit(Vec3(1, 0, 0.6), margin));  // 31.0 degrees up
  EXPECT_TRUE(within_climb_limit(Vec3(0, 0, -1), 0.0));       // no margin: straight down is allowed
}

}  // namespace peg3d
