// Sight between an eye and a sphere (sense/line_of_sight.hpp): the sight points lie where documented, and a
// sphere is in sight exactly when one of the segments to its points, up to where it enters the sphere, stays clear
// of the solids: analytic for spheres and upright cylinders, at random places, sizes and point counts.
#include "sense/line_of_sight.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "core/random.hpp"
#include "support/draws.hpp"
#include "world/arena.hpp"
#include "world/world_test_support.hpp"

namespace peg3d::sense {
namespace {

// How near a segment may pass a solid's surface before the look is skipped as grazing (metres).
constexpr double kGraze = 1e-6;

using testing::uniform_draw;

// The distance from p to the segment [a, b].
double to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Whether the segment [a, b] passes through the inside of the upright solid cylinder on `base` with radius r,
// between heights z0 and z1 above the base: the parameter interval inside the radius (a quadratic) and the one
// between the heights (a slab) overlap within [0, 1] by more than a point.
bool segment_meets_cylinder(const Vec3& a, const Vec3& b, const Vec3& base, double r, double z0, double z1) {
  const Vec3 d = b - a, o = a - base;
  double lo = 0, hi = 1;
  const double qa = d.x() * d.x() + d.y() * d.y();
  const double qb = 2 * (o.x() * d.x() + o.y() * d.y());
  const double qc = o.x() * o.x() + o.y() * o.y() - r * r;
  if (qa == 0) {
    if (qc >= 0) return false;
  } else {
    const double disc = qb * qb - 4 * qa * qc;
    if (disc <= 0) return false;
    lo = std::max(lo, (-qb - std::sqrt(disc)) / (2 * qa));
    hi = std::min(hi, (-qb + std::sqrt(disc)) / (2 * qa));
  }
  if (d.z() == 0) {
    if (o.z() <= z0 || o.z() >= z1) return false;
  } else {
    const double t0 = (z0 - o.z()) / d.z(), t1 = (z1 - o.z()) / d.z();
    lo = std::max(lo, std::min(t0, t1));
    hi = std::min(hi, std::max(t0, t1));
  }
  return lo < hi;
}

TEST(SenseLineOfSight, PointsAreTheCentreThenEvenlyOnTheRimCircleStartingUp) {
  Rng rng(3);
  for (int q = 0; q < 200; ++q) {
    const Vec3 eye(uniform_draw(rng, -5, 5), uniform_draw(rng, -5, 5), uniform_draw(rng, -5, 5));
    const Vec3 c(uniform_draw(rng, -5, 5), uniform_draw(rng, -5, 5), uniform_draw(rng, -5, 5));
    const double r = uniform_draw(rng, 0.1, 1.0);
    const int n = 1 + q % kMaxSightPoints;
    std::array<Vec3, kMaxSightPoints> p;
    sight_points(eye, c, r, n, p);
    EXPECT_EQ(p[0], c);
    const Vec3 axis = (c - eye).normalized();
    for (int k = 1; k < n; ++k) {
      const Vec3 off = p[std::size_t(k)] - c;
      EXPECT_NEAR(off.norm(), kRimFraction * r, 1e-12);
      EXPECT_NEAR(off.dot(axis), 0.0, 1e-12);
      // Evenly spaced: the angle between neighbours is 2 pi / (n - 1).
      const Vec3 next = p[std::size_t(k == n - 1 ? 1 : k + 1)] - c;
      if (n > 2) {
        EXPECT_NEAR(std::acos(std::clamp(off.dot(next) / off.squaredNorm(), -1.0, 1.0)), 2 * kPi / (n - 1), 1e-6);
      }
    }
    if (n > 1) {
      // The first rim point is the highest.
      for (int k = 2; k < n; ++k) EXPECT_GE(p[1].z(), p[std::size_t(k)].z() - 1e-12);
    }
  }
}

TEST(SenseLineOfSight, InSightExactlyWhenASegmentToAPointClearsEverySolid) {
  // Random spheres and cylinders in a room; eyes and target spheres at random places outside them. The expected
  // answer: some sight point whose segment from the eye, up to where it enters the target, keeps every solid
  // farther than its radius.
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    Rng rng(seed);
    world::MapSpec m = world::testing::empty_spec({30, 30, 12}, 0.5, 5.0);
    for (int k = 0; k < 25; ++k) {
      m.spheres.push_back({{uniform_draw(rng, 4, 26), uniform_draw(rng, 4, 26), uniform_draw(rng, 2, 10)}, uniform_draw(rng, 0.5, 3.0)});
      m.cylinders.push_back({{uniform_draw(rng, 4, 26), uniform_draw(rng, 4, 26), 0.0}, uniform_draw(rng, 0.3, 1.5), uniform_draw(rng, 2, 12)});
    }
    const auto arena = world::Arena::build(m);
    const StaticRayScene scene(*arena);
    WorldAtInstant w;
    w.scene = &scene;
    const auto inside_solid = [&](const Vec3& p, double margin) {
      for (const auto& s : m.spheres)
        if ((p - s.center).norm() < s.radius + margin) return true;
      for (const auto& c : m.cylinders) {
        const Vec3 d = p - c.base;
        if (Vec3(d.x(), d.y(), 0).norm() < c.radius + margin && d.z() > -margin && d.z() < c.height + margin) return true;
      }
      return false;
    };
    // Whether a segment meets a solid, judged twice: against the solids shrunk and grown by kGraze. Where the two
    // answers differ the segment grazes a solid, and the look is skipped (float casting may judge it either way).
    const auto segment_meets = [&](const Vec3& a, const Vec3& b, bool& grazing) {
      bool meets = false;
      for (const auto& s : m.spheres) {
        const double d = to_segment(s.center, a, b) - s.radius;
        grazing = grazing || std::abs(d) < kGraze;
        meets = meets || d < 0;
      }
      for (const auto& c : m.cylinders) {
        const bool inner = segment_meets_cylinder(a, b, c.base, c.radius - kGraze, kGraze, c.height - kGraze);
        const bool outer = segment_meets_cylinder(a, b, c.base, c.radius + kGraze, -kGraze, c.height + kGraze);
        grazing = grazing || inner != outer;
        meets = meets || inner;
      }
      return meets;
    };
    int seen = 0, hidden = 0;
    for (int q = 0; q < 300; ++q) {
      Vec3 eye, c;
      const double r = uniform_draw(rng, 0.1, 0.6);
      do eye = Vec3(uniform_draw(rng, 0.5, 29.5), uniform_draw(rng, 0.5, 29.5), uniform_draw(rng, 0.5, 11.5));
      while (inside_solid(eye, 0.1));
      do c = Vec3(uniform_draw(rng, 0.5, 29.5), uniform_draw(rng, 0.5, 29.5), uniform_draw(rng, 0.5, 11.5));
      while (inside_solid(c, r + 0.01) || (c - eye).norm() < r + 0.1);
      const int points = 1 + q % kMaxSightPoints;
      std::array<Vec3, kMaxSightPoints> p;
      sight_points(eye, c, r, points, p);
      bool want = false, grazing = false;
      for (int k = 0; k < points; ++k) {
        const Ray ray{eye, (p[std::size_t(k)] - eye).normalized()};
        const double entry = *ray_sphere(ray, c, r, (p[std::size_t(k)] - eye).norm());
        want = want || !segment_meets(eye, ray.at(entry), grazing);
      }
      if (grazing) continue;
      const bool got = line_of_sight(w, eye, c, r, points);
      ASSERT_EQ(got, want) << "seed " << seed << ", look " << q << ", " << points << " points";
      (got ? seen : hidden) += 1;
    }
    EXPECT_GT(seen, 30);  // both answers are tested, on every seed
    EXPECT_GT(hidden, 30);
  }
}

TEST(SenseLineOfSight, MorePointsSeeWhatTheCentreAloneMisses) {
  // A pole between the eye and a sphere, thinner than the sphere: the centre's ray is blocked, a rim point's is not.
  world::MapSpec m = world::testing::empty_spec({20, 20, 10}, 0.5, 5.0);
  m.cylinders.push_back({{10, 10, 0}, 0.1, 10});
  m.cylinders.push_back({{14.47, 5, 0}, 0.01, 10});  // a wire 0.02 m in front of the second sphere
  const auto arena = world::Arena::build(m);
  const StaticRayScene scene(*arena);
  WorldAtInstant w;
  w.scene = &scene;
  const Vec3 eye(5, 10, 5), c(15, 10, 5);
  EXPECT_FALSE(line_of_sight(w, eye, c, 0.5, 1));
  EXPECT_TRUE(line_of_sight(w, eye, c, 0.5, 5));
  EXPECT_TRUE(line_of_sight(w, eye, eye + Vec3(0.2, 0, 0), 0.5, 1));  // an eye inside the sphere sees it
  // A solid just short of where the ray enters the sphere still hides the centre.
  EXPECT_FALSE(line_of_sight(w, Vec3(5, 5, 5), Vec3(15, 5, 5), 0.5, 1));
  EXPECT_TRUE(line_of_sight(w, Vec3(5, 5, 5), Vec3(15, 5, 5), 0.5, 5));  // rim points beside the wire
}

}  // namespace
}  // namespace peg3d::sense
