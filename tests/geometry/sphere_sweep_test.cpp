#include "geometry/sphere_sweep.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace peg3d {
namespace {

TEST(SphereSweep, HeadOnApproachTouchesAtTheAnalyticFraction) {
  // 10 m apart closing at 2 + 4 = 6 m over the step; reach 1 m: touching after 9 m of closing, t = 1.5 > 1 in
  // one step of 6 m; with a 12 m step, t = 9 / 12.
  EXPECT_FALSE(first_contact({0, 0, 0}, {2, 0, 0}, {10, 0, 0}, {6, 0, 0}, 1.0).has_value());
  const auto t = first_contact({0, 0, 0}, {4, 0, 0}, {10, 0, 0}, {2, 0, 0}, 1.0);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 9.0 / 12.0, 1e-15);
}

TEST(SphereSweep, CrossingPathsAndMisses) {
  // a moves along x through the origin, b stands 0.5 m off its path: with reach 1 they touch when
  // |x| = sqrt(1 - 0.25); a starts at x = -2 and moves 4 m, so t = (2 - sqrt(0.75)) / 4.
  const auto t = first_contact({-2, 0, 0}, {2, 0, 0}, {0, 0.5, 0}, {0, 0.5, 0}, 1.0);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, (2.0 - std::sqrt(0.75)) / 4.0, 1e-15);
  // 1.5 m off the path: never within 1 m.
  EXPECT_FALSE(first_contact({-2, 0, 0}, {2, 0, 0}, {0, 1.5, 0}, {0, 1.5, 0}, 1.0).has_value());
  // Moving in parallel at the same velocity: the distance never changes.
  EXPECT_FALSE(first_contact({0, 0, 0}, {5, 0, 0}, {0, 2, 0}, {5, 2, 0}, 1.0).has_value());
  // Moving apart: no contact even if the closest approach of the lines is near.
  EXPECT_FALSE(first_contact({0, 0, 0}, {-1, 0, 0}, {2, 0, 0}, {3, 0, 0}, 1.0).has_value());
}

TEST(SphereSweep, AlreadyTouchingIsContactAtTheStart) {
  EXPECT_EQ(first_contact({0, 0, 0}, {1, 0, 0}, {0.5, 0, 0}, {0.5, 0, 0}, 1.0), 0.0);
  // A fast pass straight through the other in one step is still a contact (no tunnelling).
  const auto t = first_contact({-100, 0, 0}, {100, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0.5);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 99.5 / 200.0, 1e-15);
}

}  // namespace
}  // namespace peg3d
