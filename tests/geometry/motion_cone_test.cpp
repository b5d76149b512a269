#include "geometry/motion_cone.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

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

namespace peg3d {
namespace {

TEST(MotionCone, ProjectionWithinBandSatisfiesConeAndBand) {
  Rng rng(29);
  const double margin = kPi / 3;
  for (int trial = 0; trial < 2000; ++trial) {
    // A cone reaches the band when its half-angle exceeds the axis's angular distance to the band.
    const Vec3 axis = testing::random_unit(rng);
    const double theta = heading_of(axis).theta;
    const double gap = std::max({0.0, margin - theta, theta - (kPi - margin)});
    const Cone cone{axis, std::uniform_real_distribution<double>(gap + 0.01, kPi / 2 + 0.01)(rng)};
    const Vec3 q = project_within_band(cone, testing::random_unit(rng), margin);
    EXPECT_NEAR(q.norm(), 1.0, 1e-12);
    EXPECT_TRUE(cone.contains(q, 1e-9));
    EXPECT_GE(heading_of(q).theta, margin - 1e-9);
    EXPECT_LE(heading_of(q).theta, kPi - margin + 1e-9);
  }
}

TEST(MotionCone, ProjectionWithinBandPrefersTheBandEdgeNearestTheRequest) {
  // Obstacle straight ahead (+x): the half-space away from it contains no direction pointing +x; a heading
  // straight at it must end level-ish and sideways, never diving towards the obstacle.
  const Cone away{-Vec3::UnitX(), kPi / 2};
  const Vec3 q = project_within_band(away, Vec3::UnitX(), kPi / 3);
  EXPECT_LE(q.x(), 1e-9);
  EXPECT_GE(heading_of(q).theta, kPi / 3 - 1e-9);
  EXPECT_LE(heading_of(q).theta, 2 * kPi / 3 + 1e-9);
}

}  // namespace
}  // namespace peg3d

namespace peg3d {
namespace {

TEST(MotionCone, FirstInsideOnArcLandsOnTheConeBoundary) {
  Rng rng(31);
  for (int trial = 0; trial < 1000; ++trial) {
    const Cone cone{testing::random_unit(rng), std::uniform_real_distribution<double>(0.2, 2.5)(rng)};
    const Vec3 from = testing::random_unit(rng);
    const Vec3 q = first_inside_on_arc(cone, from, cone.axis);
    EXPECT_TRUE(cone.contains(q, 1e-9));
    if (!cone.contains(from)) {
      EXPECT_NEAR(angle_between(q, cone.axis), cone.half_angle, 1e-8);
    }
    // q lies on the arc from `from` to the axis.
    EXPECT_NEAR(angle_between(from, q) + angle_between(q, cone.axis), angle_between(from, cone.axis), 1e-8);
  }
}

}  // namespace
}  // namespace peg3d

namespace peg3d {
namespace {

// ConeMembership answers as contains() for every direction, far from the surface and on it: directions
// drawn at random, and directions placed at the cone's angle plus offsets down to a few ulps.
TEST(MotionCone, BoundaryCrossingsOfTwoHalfSpacesAreTheirCommonEdge) {
  // Two half-spaces x >= 0 and y >= 0: their boundary planes meet in the z axis.
  const auto both = boundary_crossings(Cone{Vec3::UnitX(), kPi / 2}, Cone{Vec3::UnitY(), kPi / 2});
  ASSERT_EQ(both.count, 2);
  EXPECT_TRUE(both.at[0].isApprox(Vec3::UnitZ(), 1e-12));
  EXPECT_TRUE(both.at[1].isApprox(-Vec3::UnitZ(), 1e-12));
  // Cones of 60 degrees about x and y: u . x = u . y = 1/2, so u = (1/2, 1/2, +-1/sqrt(2)).
  const auto narrow = boundary_crossings(Cone{Vec3::UnitX(), kPi / 3}, Cone{Vec3::UnitY(), kPi / 3});
  ASSERT_EQ(narrow.count, 2);
  for (const Vec3& u : narrow) {
    EXPECT_NEAR(u.x(), 0.5, 1e-12);
    EXPECT_NEAR(u.y(), 0.5, 1e-12);
    EXPECT_NEAR(std::abs(u.z()), std::sqrt(0.5), 1e-12);
  }
  // Cones of 45 degrees about x and y only touch, along (1, 1, 0); 30 degree ones do not meet.
  const auto touch = boundary_crossings(Cone{Vec3::UnitX(), kPi / 4}, Cone{Vec3::UnitY(), kPi / 4});
  ASSERT_EQ(touch.count, 1);
  EXPECT_TRUE(touch.at[0].isApprox(Vec3(1, 1, 0).normalized(), 1e-6));
  EXPECT_EQ(boundary_crossings(Cone{Vec3::UnitX(), kPi / 6}, Cone{Vec3::UnitY(), kPi / 6}).count, 0);
  EXPECT_EQ(boundary_crossings(Cone{Vec3::UnitX(), kPi / 2}, Cone{-Vec3::UnitX(), kPi / 2}).count, 0);
}

TEST(MotionCone, MembershipAndContainsAnswerAsTheAngleEverywhere) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> half(0.0, kPi), offset_exp(-17.0, -1.0);
  const auto random_unit = [&] { return Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized(); };
  int near_surface = 0;
  for (int c = 0; c < 2000; ++c) {
    const Cone cone{random_unit(), c % 10 == 0 ? 0.0 : (c % 10 == 1 ? kPi : half(rng))};
    const ConeMembership inside(cone);
    for (int k = 0; k < 200; ++k) {
      Vec3 d = random_unit() * std::exp(gauss(rng));  // not unit: contains() takes any non-zero length
      if (k % 2 == 0) {
        // At the surface: rotate the axis by the half angle plus a tiny signed offset, about a perpendicular.
        const Vec3 side = cone.axis.cross(random_unit()).normalized();
        const double a = cone.half_angle + (k % 4 == 0 ? 1.0 : -1.0) * std::pow(10.0, offset_exp(rng));
        d = std::cos(a) * cone.axis + std::sin(a) * side;
        ++near_surface;
      }
      ASSERT_EQ(inside(d), cone.contains(d)) << "cone half angle " << cone.half_angle << ", direction " << d.transpose();
      for (const double tolerance : {1e-12, 1e-9, 0.0}) {
        ASSERT_EQ(cone.contains(d, tolerance), angle_between(d, cone.axis) <= cone.half_angle + tolerance)
            << "cone half angle " << cone.half_angle << ", direction " << d.transpose();
      }
    }
  }
  EXPECT_GT(near_surface, 100000);
}

}  // namespace
}  // namespace peg3d

namespace peg3d {
namespace {

// What Cone::contains is defined as, with none of its shortcuts.
bool reference_contains(const Cone& cone, const Vec3& d, double tolerance = 1e-12) {
  return angle_between(d, cone.axis) <= cone.half_angle + tolerance;
}

// The two searches as they were written before their closed-form start: 40 halvings of [0, 1], each asking
// the reference membership. The library's versions must return the same bits.
Vec3 band_by_halving(const Cone& cone, const Vec3& d, double margin) {
  const Vec3 c = cone.project(d, Vec3::Zero(), 0.0);
  const Heading hc = heading_of(c);
  if (hc.theta >= margin && hc.theta <= kPi - margin) return c;
  const double edge = hc.theta < margin ? margin : kPi - margin;
  const Heading ha = heading_of(cone.axis);
  const bool axis_vertical = cone.axis.x() == 0.0 && cone.axis.y() == 0.0;
  const double a0 = hc.alpha, a1 = axis_vertical ? hc.alpha : a0 + wrap_angle(ha.alpha - a0);
  const auto on_edge = [&](double alpha) { return direction(Heading{alpha, edge}); };
  if (reference_contains(cone, on_edge(a0))) return on_edge(a0);
  if (!reference_contains(cone, on_edge(a1))) return on_edge(a1);
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (reference_contains(cone, on_edge(a0 + mid * (a1 - a0))) ? hi : lo) = mid;
  }
  return on_edge(a0 + hi * (a1 - a0));
}

Vec3 arc_by_halving(const Cone& cone, const Vec3& from, const Vec3& to) {
  if (reference_contains(cone, from)) return from;
  const double omega = angle_between(from, to);
  if (omega < 1e-12) return to;
  const Vec3 side = omega > kPi - 1e-9 ? any_perpendicular(from) : Vec3((to - std::cos(omega) * from).normalized());
  const auto at = [&](double t) { return Vec3(std::cos(t * omega) * from + std::sin(t * omega) * side); };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (reference_contains(cone, at(mid)) ? hi : lo) = mid;
  }
  return at(hi).normalized();
}

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }

TEST(MotionCone, BandAndArcSearchesReturnTheBitsOfPlainHalving) {
  Rng rng(41);
  std::uniform_real_distribution<double> half(0.0, kPi), margin(0.05, kPi / 3);
  int band_searches = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Cone cone{testing::random_unit(rng), half(rng)};
    const Vec3 d = testing::random_unit(rng);
    const double m = margin(rng);
    const Vec3 expected = band_by_halving(cone, d, m);
    ASSERT_TRUE(same_bits(project_within_band(cone, d, m), expected)) << "trial " << trial;
    const Heading hc = heading_of(cone.project(d, Vec3::Zero(), 0.0));
    band_searches += hc.theta < m || hc.theta > kPi - m;
    // Arcs towards the axis and towards any direction (which may stay outside).
    for (const Vec3& to : {cone.axis, testing::random_unit(rng)}) {
      const Vec3 from = testing::random_unit(rng);
      ASSERT_TRUE(same_bits(first_inside_on_arc(cone, from, to), arc_by_halving(cone, from, to))) << "trial " << trial;
    }
  }
  EXPECT_GT(band_searches, 1000);
}

}  // namespace
}  // namespace peg3d
