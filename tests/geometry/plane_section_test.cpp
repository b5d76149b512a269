#include "geometry/plane_section.hpp"

#include <random>

#include <gtest/gtest.h>

namespace peg3d {
namespace {

const Box kSectionBox{{0, 0, 0}, {35, 35, 20}};

Vec3 centroid_of(const Vec3& point, const Vec3& normal, const Box& box, std::span<const HalfSpace> cuts = {}) {
  std::vector<Vec3> corners, scratch;
  plane_section(point, normal, box, cuts, corners, scratch);
  EXPECT_FALSE(corners.empty());
  for (const Vec3& c : corners) {
    EXPECT_NEAR((c - point).dot(normal), 0.0, 1e-9);  // on the plane
    EXPECT_TRUE(box.shrunk(-1e-9).contains(c));        // in the box
  }
  return corners.empty() ? Vec3::Zero() : polygon_centroid(corners, normal);
}

TEST(PlaneSection, EveryPlaneThroughTheBoxsCentreCutsItAboutTheCentre) {
  // The box is symmetric about its centre, so is every section through it: its centroid is the centre.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  for (int i = 0; i < 100; ++i) {
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    EXPECT_LT((centroid_of(kSectionBox.center(), n, kSectionBox) - kSectionBox.center()).norm(), 1e-9) << n.transpose();
  }
}

TEST(PlaneSection, ACornerCutIsATriangle) {
  // x + y + z = k cuts the unit cube's corner at the origin in the triangle (k,0,0), (0,k,0), (0,0,k) for k < 1.
  const Box cube{{0, 0, 0}, {1, 1, 1}};
  const Vec3 n = Vec3(1, 1, 1).normalized();
  for (const double k : {0.05, 0.3, 0.77, 0.999}) {
    std::vector<Vec3> corners, scratch;
    plane_section(Vec3(k, 0, 0), n, cube, {}, corners, scratch);
    EXPECT_EQ(corners.size(), 3u);
    EXPECT_LT((polygon_centroid(corners, n) - Vec3(k, k, k) / 3.0).norm(), 1e-12) << k;
  }
}

TEST(PlaneSection, HalfSpacesCutTheSectionDown) {
  // z = h, kept where x <= c (and where -y <= -a: y >= a): the rectangle [0, c] x [a, 35] at height h.
  for (const double h : {0.5, 7.3, 19.0}) {
    for (const double c : {1.0, 12.5, 34.0}) {
      const double a = 0.25 * c;
      const HalfSpace cuts[] = {{Vec3::UnitX(), c}, {-Vec3::UnitY(), -a}};
      const Vec3 expected(0.5 * c, 0.5 * (a + 35.0), h);
      EXPECT_LT((centroid_of({3, 30, h}, Vec3::UnitZ(), kSectionBox, cuts) - expected).norm(), 1e-9) << h << " " << c;
    }
  }
}

TEST(PlaneSection, APlaneThatMissesGivesNoCorners) {
  std::vector<Vec3> corners, scratch;
  plane_section({10, 10, 21}, Vec3::UnitZ(), kSectionBox, {}, corners, scratch);
  EXPECT_TRUE(corners.empty());
  const HalfSpace all_out[] = {{Vec3::UnitX(), -1.0}};  // x <= -1
  plane_section({10, 10, 5}, Vec3::UnitZ(), kSectionBox, all_out, corners, scratch);
  EXPECT_TRUE(corners.empty());
}

}  // namespace
}  // namespace peg3d
