// Rays against solids (geometry/ray.hpp), each against its analytic answer over random centres, sizes, angles
// and offsets: the entry distance to 1e-9 m, grazing rays that touch and rays a nanometre off that miss, rays
// that start inside (distance 0), behind or beyond range (no hit); and posed shapes checked point by point
// against their exact signed distance.
#include "geometry/ray.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/draws.hpp"
#include "support/numbers.hpp"
#include "test_vectors.hpp"

namespace peg3d {
namespace {

using testing::random_point;
using testing::random_unit;

constexpr double kTol = 1e-9;

// A unit vector perpendicular to d.
Vec3 perpendicular(const Vec3& d, Rng& rng) {
  Vec3 n;
  do n = random_unit(rng).cross(d);
  while (n.norm() < 1e-3);
  return n.normalized();
}

using testing::kInf;
using testing::uniform_draw;

TEST(RaySphere, EntersAtTheAnalyticDistanceForAnyOffsetAndAngle) {
  Rng rng(11);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 c = random_point(rng);
    const double r = uniform_draw(rng, 0.05, 5.0), L = uniform_draw(rng, r + 0.01, 40.0), p = uniform_draw(rng, 0.0, r);
    const Vec3 d = random_unit(rng), n = perpendicular(d, rng);
    const Ray ray{c - L * d + p * n, d};  // passes p from the centre, L before its foot
    const auto t = ray_sphere(ray, c, r, 100.0);
    ASSERT_TRUE(t) << k;
    EXPECT_NEAR(*t, L - std::sqrt(r * r - p * p), kTol) << k;
    EXPECT_FALSE(ray_sphere({c + L * d + p * n, d}, c, r, 100.0)) << "behind, " << k;
    EXPECT_FALSE(ray_sphere({c - L * d + uniform_draw(rng, 1.0 + 1e-6, 3.0) * r * n, d}, c, r, 100.0)) << "beside, " << k;
    EXPECT_FALSE(ray_sphere(ray, c, r, *t - 1e-6)) << "beyond range, " << k;
    EXPECT_EQ(ray_sphere({c + uniform_draw(rng, 0.0, 0.999) * r * random_unit(rng), d}, c, r, 100.0), 0.0) << "inside";
  }
}

TEST(RaySphere, AGrazingRayTouchesAndOneANanometreOutMisses) {
  // Tangent at the origin: |m|^2 - r^2 and b^2 are exact, so the discriminant is exactly 0.
  const auto t = ray_sphere({{-5, 0, 0}, {1, 0, 0}}, {0, 1, 0}, 1.0, 100.0);
  ASSERT_TRUE(t);
  EXPECT_EQ(*t, 5.0);
  EXPECT_FALSE(ray_sphere({{-5, -1e-9, 0}, {1, 0, 0}}, {0, 1, 0}, 1.0, 100.0));
  EXPECT_EQ(ray_sphere({{0, 0, 0}, {1, 0, 0}}, {0, 1, 0}, 1.0, 100.0), 0.0);  // starts on the surface
}

TEST(RayUprightCylinder, EntersTheSideAtTheAnalyticDistance) {
  Rng rng(12);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 base = random_point(rng);
    const double r = uniform_draw(rng, 0.1, 4.0), h = uniform_draw(rng, 0.5, 15.0);
    const double az = uniform_draw(rng, -M_PI, M_PI), L = uniform_draw(rng, r + 0.01, 30.0), p = uniform_draw(rng, 0.0, r);
    const Vec3 d(std::cos(az), std::sin(az), 0.0), n(-std::sin(az), std::cos(az), 0.0);
    const double z = uniform_draw(rng, 0.0, h);
    const Vec3 foot = base + Vec3(0, 0, z) + p * n;
    const auto t = ray_upright_cylinder({foot - L * d, d}, base, r, h, 100.0);
    ASSERT_TRUE(t) << k;
    EXPECT_NEAR(*t, L - std::sqrt(r * r - p * p), kTol) << k;
    // Tilted by an elevation e, the ray meets the side at the same horizontal run when it is still between the
    // caps there.
    const double e = uniform_draw(rng, -0.6, 0.6), run = L - std::sqrt(r * r - p * p);
    const Vec3 de = (std::cos(e) * d + Vec3(0, 0, std::sin(e))).normalized();
    const double dz_at_side = run * std::tan(e);
    const Vec3 origin = foot - L * d - dz_at_side * Vec3::UnitZ();
    const auto te = ray_upright_cylinder({origin, de}, base, r, h, 100.0);
    const double z_at_side = origin.z() - base.z() + dz_at_side;
    if (z_at_side > 1e-6 && z_at_side < h - 1e-6) {
      // It meets the side there, unless it crossed a cap's plane inside the disc before (from above or below).
      double expected = run / std::cos(e);
      for (const double plane : {0.0, h}) {
        const double tc = (plane - (origin.z() - base.z())) / de.z();
        if (de.z() == 0.0 || tc < 0.0 || tc >= expected) continue;
        if ((origin + tc * de - base).head<2>().norm() <= r) expected = tc;
      }
      ASSERT_TRUE(te) << k;
      EXPECT_NEAR(*te, expected, kTol) << k;
    }
    EXPECT_FALSE(ray_upright_cylinder({foot - L * d + uniform_draw(rng, 1.0 + 1e-6, 2.0) * r * n - p * n, d}, base, r, h, 100.0))
        << "beside, " << k;
    EXPECT_FALSE(ray_upright_cylinder({foot - L * d + Vec3(0, 0, h + 0.01), d}, base, r, h, 100.0)) << "above, " << k;
  }
}

TEST(RayUprightCylinder, EntersTheCapsAtTheAnalyticDistance) {
  Rng rng(13);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 base = random_point(rng);
    const double r = uniform_draw(rng, 0.1, 4.0), h = uniform_draw(rng, 0.5, 15.0);
    // A point of the top (or bottom) disc, and a ray reaching it from above (below) at a polar angle of up to
    // 60 degrees; over that short a height above the cap it cannot have met the side first when the point
    // is well inside.
    const double rho = uniform_draw(rng, 0.0, 0.5 * r), phi = uniform_draw(rng, -M_PI, M_PI);
    const bool top = k % 2 == 0;
    const Vec3 on_cap = base + Vec3(rho * std::cos(phi), rho * std::sin(phi), top ? h : 0.0);
    const double polar = uniform_draw(rng, 0.0, M_PI / 3.0), az = uniform_draw(rng, -M_PI, M_PI);
    const double lift = uniform_draw(rng, 0.01, 0.25 * r);  // height of the origin over the cap's plane
    Vec3 d(std::sin(polar) * std::cos(az), std::sin(polar) * std::sin(az), top ? -std::cos(polar) : std::cos(polar));
    const double t_expected = lift / std::cos(polar);
    const Vec3 origin = on_cap - t_expected * d;
    const auto t = ray_upright_cylinder({origin, d}, base, r, h, 100.0);
    ASSERT_TRUE(t) << k;
    EXPECT_NEAR(*t, t_expected, kTol) << k;
  }
  // Along the axis from above: the top cap; parallel to the axis outside the column: nothing; the rim's edge
  // exactly: a touch.
  EXPECT_EQ(ray_upright_cylinder({{0, 0, 10}, {0, 0, -1}}, {0, 0, 0}, 1.0, 4.0, 100.0), 6.0);
  EXPECT_FALSE(ray_upright_cylinder({{1.5, 0, 10}, {0, 0, -1}}, {0, 0, 0}, 1.0, 4.0, 100.0));
  EXPECT_EQ(ray_upright_cylinder({{1, 0, 10}, {0, 0, -1}}, {0, 0, 0}, 1.0, 4.0, 100.0), 6.0);
  EXPECT_EQ(ray_upright_cylinder({{0.5, 0, 2}, {0, 0, 1}}, {0, 0, 0}, 1.0, 4.0, 100.0), 0.0);  // inside
}

// The entry functions (no range, +infinity for a miss), which casters test many solids with, answer exactly as
// the ranged ones: the same distance to the bit, a miss where those find none. (Their distances are checked
// against the analytic ones above, through the ranged functions.)
TEST(RayEntry, AgreesWithTheRangedTestsToTheBit) {
  Rng rng(17);
  int met = 0, missed = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 origin = random_point(rng, 10.0), centre = random_point(rng, 10.0);
    // Half the rays aimed near the solid, half anywhere.
    const Vec3 aim = centre + random_point(rng, 3.0) - origin;
    const Ray ray{origin, k % 2 == 0 && aim.norm() > 1e-6 ? Vec3(aim.normalized()) : random_unit(rng)};
    const double r = uniform_draw(rng, 0.1, 5.0), h = uniform_draw(rng, 0.5, 15.0), range = uniform_draw(rng, 1.0, 40.0);
    const auto sphere = ray_sphere(ray, centre, r, range);
    const double sphere_entry = ray_sphere_entry(ray, centre, r);
    EXPECT_EQ(sphere.value_or(kInf), sphere_entry <= range ? sphere_entry : kInf) << k;
    const auto cylinder = ray_upright_cylinder(ray, centre, r, h, range);
    const double cylinder_entry = ray_upright_cylinder_entry(ray, centre, r, h);
    EXPECT_EQ(cylinder.value_or(kInf), cylinder_entry <= range ? cylinder_entry : kInf) << k;
    (cylinder ? met : missed) += 1;
  }
  EXPECT_GT(met, 2000);
  EXPECT_GT(missed, 2000);
  // A miss stays a miss without a bound on the range.
  const Ray away{{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE(ray_sphere(away, {-5, 0, 0}, 1.0, kInf));
  EXPECT_FALSE(ray_upright_cylinder(away, {-5, 0, 0}, 1.0, 2.0, kInf));
  EXPECT_FALSE(ray_box(away, {-6, -1, -1}, {-4, 1, 1}, kInf));
  // Parallel to the axis: inside the column it meets the cylinder, outside it misses (a = 0 in column_cut).
  EXPECT_FALSE(column_cut({{0.5, 0, 10}, {0, 0, -1}}, {0, 0, 0}, 1.0).misses());
  EXPECT_TRUE(column_cut({{1.5, 0, 10}, {0, 0, -1}}, {0, 0, 0}, 1.0).misses());
}

TEST(RayBox, EntersAFaceAtTheAnalyticDistance) {
  Rng rng(14);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 lo = random_point(rng);
    const Vec3 hi = lo + Vec3(uniform_draw(rng, 0.1, 8), uniform_draw(rng, 0.1, 8), uniform_draw(rng, 0.1, 8));
    const int axis = k % 3;
    const bool upper = (k / 3) % 2 == 0;
    // A point of one face, reached from outside at up to 70 degrees from its normal, from a short way off.
    Vec3 on_face;
    for (int j = 0; j < 3; ++j) on_face[j] = uniform_draw(rng, lo[j] + 0.3 * (hi[j] - lo[j]), hi[j] - 0.3 * (hi[j] - lo[j]));
    on_face[axis] = upper ? hi[axis] : lo[axis];
    Vec3 d = -random_unit(rng);
    if ((upper && d[axis] > 0) || (!upper && d[axis] < 0)) d[axis] = -d[axis];
    if (std::abs(d[axis]) < 0.35) continue;
    const double gap = uniform_draw(rng, 1e-3, 0.25 * std::min({hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z()}));
    const double t_expected = gap / std::abs(d[axis]);
    const auto t = ray_box({on_face - t_expected * d, d}, lo, hi, 100.0);
    ASSERT_TRUE(t) << k;
    EXPECT_NEAR(*t, t_expected, kTol) << k;
    EXPECT_EQ(ray_box({0.5 * (lo + hi), d}, lo, hi, 100.0), 0.0) << "inside";
    EXPECT_FALSE(ray_box({on_face - t_expected * d, -d}, lo, hi, 100.0)) << "heading away, " << k;
  }
  // A corner touched exactly, an edge grazed, and a ray along a face's plane just outside.
  EXPECT_EQ(ray_box({{-1, -1, -1}, Vec3(1, 1, 1).normalized()}, {0, 0, 0}, {1, 1, 1}, 100.0).has_value(), true);
  EXPECT_EQ(ray_box({{-1, 0, 0}, {1, 0, 0}}, {0, 0, 0}, {1, 1, 1}, 100.0), 1.0);
  EXPECT_FALSE(ray_box({{-1, -1e-9, 0.5}, {1, 0, 0}}, {0, 0, 0}, {1, 1, 1}, 100.0));
}

TEST(RayTriangle, MeetsAnyPointOfTheTriangleFromEitherSide) {
  Rng rng(15);
  for (int k = 0; k < 4000; ++k) {
    const Vec3 a = random_point(rng), b = a + random_point(rng, 5.0), c = a + random_point(rng, 5.0);
    const Vec3 normal = (b - a).cross(c - a);
    if (normal.norm() < 1.0) continue;  // a sliver: its plane is ill-defined to 1e-9
    double u = uniform_draw(rng, 0, 1), v = uniform_draw(rng, 0, 1);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Vec3 p = a + u * (b - a) + v * (c - a);
    Vec3 d = random_unit(rng);
    if (std::abs(d.dot(normal.normalized())) < 0.1) continue;  // nearly edge-on
    const double L = uniform_draw(rng, 0.0, 30.0);
    const auto t = ray_triangle({p - L * d, d}, a, b, c, 100.0);
    ASSERT_TRUE(t) << k;
    EXPECT_NEAR(*t, L, kTol * (1.0 + L)) << k;
    const auto back = ray_triangle({p + L * d, -d}, a, b, c, 100.0);  // from the other side
    ASSERT_TRUE(back) << k;
    EXPECT_NEAR(*back, L, kTol * (1.0 + L)) << k;
    // Outside the triangle across edge bc (u + v > 1): no hit.
    const Vec3 out = a + (u + 0.6) * (b - a) + (v + 0.6) * (c - a);
    EXPECT_FALSE(ray_triangle({out - L * d, d}, a, b, c, 100.0)) << k;
  }
  EXPECT_FALSE(ray_triangle({{-1, 0.2, 0}, {1, 0, 0}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 100.0));  // edge-on
  EXPECT_EQ(ray_triangle({{0.5, 0, 1}, {0, 0, -1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 100.0), 1.0);  // on an edge
}

TEST(RayShape, PosedShapesAgreeWithTheirSignedDistancePointByPoint) {
  // The hit point lies on the surface (signed distance 0 to 1e-9), the ray is outside everywhere before it, and
  // a ray that misses stays outside along its whole range (sampled every 5 mm).
  Rng rng(16);
  int hits = 0, misses = 0;
  for (int k = 0; k < 600; ++k) {
    Shape s;
    s.kind = static_cast<Shape::Kind>(k % 3);
    s.radius = uniform_draw(rng, 0.2, 2.0);
    s.height = uniform_draw(rng, 0.4, 4.0);
    s.size = Vec3(uniform_draw(rng, 0.3, 3), uniform_draw(rng, 0.3, 3), uniform_draw(rng, 0.3, 3));
    const Pose pose{random_point(rng, 5.0), Quat(Eigen::AngleAxisd(uniform_draw(rng, 0, M_PI), random_unit(rng)))};
    Vec3 origin;
    do origin = random_point(rng, 10.0);
    while (signed_distance(s, pose, origin) <= 0.05);
    const Vec3 d = (pose.position + random_point(rng, 1.5) - origin).normalized();
    const double range = 25.0;
    const auto t = ray_shape({origin, d}, s, pose, range);
    if (t) {
      ++hits;
      EXPECT_NEAR(signed_distance(s, pose, origin + *t * d), 0.0, kTol) << k << " " << to_string(s.kind);
      for (double x = 0.0; x < *t - 1e-6; x += 0.005) ASSERT_GT(signed_distance(s, pose, origin + x * d), 0.0) << k;
    } else {
      ++misses;
      for (double x = 0.0; x <= range; x += 0.005) ASSERT_GT(signed_distance(s, pose, origin + x * d), 0.0) << k;
    }
    EXPECT_EQ(ray_shape({pose.position, d}, s, pose, range), 0.0) << "from the centre";
  }
  EXPECT_GT(hits, 200);
  EXPECT_GT(misses, 50);
}

TEST(RayBoxExit, LeavesThroughTheNearestFaceAhead) {
  Rng rng(17);
  const Vec3 lo(0, 0, 0), hi(35, 35, 20);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 o(uniform_draw(rng, 0, 35), uniform_draw(rng, 0, 35), uniform_draw(rng, 0, 20));
    const Vec3 d = random_unit(rng);
    const BoxExit exit = ray_box_exit({o, d}, lo, hi);
    const double t = exit.distance;
    const Vec3 p = o + t * d;
    // On the face it names.
    const int axis = exit.face / 2;
    EXPECT_NEAR(p[axis], exit.face % 2 == 1 ? hi[axis] : lo[axis], kTol) << k;
    // On the box's surface, and every coordinate within it.
    const double gap = std::min({p.x() - lo.x(), hi.x() - p.x(), p.y() - lo.y(), hi.y() - p.y(), p.z() - lo.z(),
                                 hi.z() - p.z()});
    EXPECT_NEAR(gap, 0.0, kTol) << k;
  }
  EXPECT_EQ(ray_box_exit({{1, 2, 3}, {0, 0, 1}}, lo, hi).distance, 17.0);
  EXPECT_EQ(ray_box_exit({{1, 2, 3}, {0, 0, 1}}, lo, hi).face, 5);
  EXPECT_EQ(ray_box_exit({{1, 2, 3}, {-1, 0, 0}}, lo, hi).face, 0);
  EXPECT_EQ(ray_box_exit({{-1, 2, 3}, {0, 0, 1}}, lo, hi).distance, 0.0);  // from outside
}

}  // namespace
}  // namespace peg3d
