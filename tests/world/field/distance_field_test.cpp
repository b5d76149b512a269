// The distance field against analytic distances: spheres, cylinders, planes (arena faces) and triangles.
// Answers must lie within one voxel diagonal of the exact distance, point towards the obstacle, and the
// early-out bound must never exceed the exact distance.

#include <cmath>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "world/arena.hpp"
#include "world/field/field_builder.hpp"
#include "world/map/obstacle_geometry.hpp"
#include "world/field/voxel_grid.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

using testing::empty_spec;

/// Closest point of triangle abc to p (barycentric region tests).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double mesh_distance(const TriangleMesh& m, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& f : m.faces) {
    best = std::min(best, (p - closest_on_triangle(p, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]])).norm());
  }
  return best;
}

std::vector<Vec3> random_points(const Box& box, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> out(std::size_t(n), Vec3::Zero());
  for (auto& p : out) p = box.lo + box.size().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
  return out;
}

/// Checks answers against an exact signed distance: within one voxel diagonal, pointing at the obstacle,
/// and the early-out bound never above the exact distance.
/// With faces_only the exact distance is to arena faces, which the early-out bound leaves out.
template <class ExactDistance>
void check_against(const Arena& arena, ExactDistance exact, int samples, bool faces_only = false) {
  const double diag = std::sqrt(3.0) * arena.resolution();
  int compared = 0;
  for (const Vec3& p : random_points(arena.bounds(), samples, 42)) {
    const double t = exact(p);
    const NearestObstacle n = arena.nearest_obstacle(p);
    if (!faces_only) {
      EXPECT_LE(arena.clearance_lower_bound(p), std::max(t, 0.0) + 1e-12) << p.transpose();
    }
    if (t <= 0.0) {
      EXPECT_TRUE(n.found);
      EXPECT_EQ(n.distance, 0.0) << p.transpose();
      continue;
    }
    if (t > arena.max_distance() - diag) continue;  // near the cap either answer is right
    ++compared;
    ASSERT_TRUE(n.found) << p.transpose();
    EXPECT_NEAR(n.distance, t, diag) << p.transpose();
    EXPECT_NEAR((n.point - p).norm(), n.distance, 1e-9);
    // The reported point lies on the obstacle to within a diagonal, and so does the point the exact
    // distance away along the reported direction: the direction points at the obstacle.
    EXPECT_LE(std::abs(exact(n.point)), diag + 1e-9) << p.transpose();
    if (n.distance > 0.0) {
      const Vec3 along = p + t * (n.point - p).normalized();
      EXPECT_LE(std::abs(exact(along)), 2 * diag + 1e-9) << p.transpose();
    }
  }
  EXPECT_GT(compared, samples / 4);
}

TEST(WorldDistanceField, SphereWithinOneVoxelDiagonal) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.1, 3.0);
  const SphereObstacle s{Vec3(5.03, 4.97, 5.01), 1.2};
  spec.spheres.push_back(s);
  const auto arena = testing::build(spec);
  check_against(*arena, [&](const Vec3& p) { return signed_distance(p, s); }, 4000);
}

TEST(WorldDistanceField, CylinderWithinOneVoxelDiagonal) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.1, 3.0);
  const CylinderObstacle c{Vec3(4.95, 5.05, 2.02), 1.1, 5.5};
  spec.cylinders.push_back(c);
  const auto arena = testing::build(spec);
  check_against(*arena, [&](const Vec3& p) { return signed_distance(p, c); }, 4000);
}

TEST(WorldDistanceField, FloorPlaneIsExact) {
  MapSpec spec = empty_spec(Vec3(8, 8, 8), 0.2, 3.0);
  spec.floor_is_obstacle = true;
  const auto arena = testing::build(spec);
  check_against(*arena, [](const Vec3& p) { return p.z(); }, 2000, true);
  // A point above the floor's lattice-aligned face: the distance is its height exactly, straight down.
  const NearestObstacle n = arena->nearest_obstacle(Vec3(3.33, 4.21, 1.37));
  EXPECT_NEAR(n.distance, 1.37, 1e-12);
  EXPECT_TRUE(n.point.isApprox(Vec3(3.33, 4.21, 0.0), 1e-12));
}

TEST(WorldDistanceField, WallsAndCeilingCountWhenConfigured) {
  MapSpec spec = empty_spec(Vec3(6, 6, 6), 0.2, 5.0);
  spec.walls_is_obstacle = true;
  spec.ceiling_is_obstacle = true;
  const auto arena = testing::build(spec);
  check_against(*arena, [](const Vec3& p) { return std::min({p.x(), p.y(), 6 - p.x(), 6 - p.y(), 6 - p.z()}); }, 2000,
                true);
}

TEST(WorldDistanceField, TriangleMeshWithinOneVoxelDiagonal) {
  MapSpec spec = empty_spec(Vec3(20, 10, 8), 0.1, 3.0);
  spec.meshes.push_back(testing::mesh_entry("ridge.obj", Vec3(0, 0, 0.5)));
  const auto arena = testing::build(spec);
  const TriangleMesh& m = arena->meshes()[0];
  auto exact = [&](const Vec3& p) { return mesh_distance(m, p); };
  check_against(*arena, exact, 1500);
}

TEST(WorldDistanceField, FacesAreExactPlanesAndCombineWithShapes) {
  MapSpec spec = empty_spec(Vec3(10, 10, 5), 0.3, 3.0);  // 5 m is not a multiple of 0.3 m: still exact
  spec.floor_is_obstacle = spec.ceiling_is_obstacle = true;
  spec.spheres.push_back({Vec3(5, 5, 2.5), 1.0});
  const auto arena = testing::build(spec);
  NearestObstacle n = arena->nearest_obstacle(Vec3(2, 2, 4.2));
  EXPECT_NEAR(n.distance, 0.8, 1e-12);
  EXPECT_TRUE(n.point.isApprox(Vec3(2, 2, 5), 1e-12));
  // Next to the sphere, the sphere wins over the floor 2 m below.
  n = arena->nearest_obstacle(Vec3(3.6, 5, 2.0));
  EXPECT_NEAR(n.distance, (Vec3(3.6, 5, 2.0) - Vec3(5, 5, 2.5)).norm() - 1.0, std::sqrt(3.0) * 0.3);
  EXPECT_LT(n.point.x(), 4.5);
  // Below the floor is inside the obstacle; walls are not obstacles here.
  n = arena->nearest_obstacle(Vec3(2, 2, -0.5));
  EXPECT_TRUE(n.found);
  EXPECT_EQ(n.distance, 0.0);
  EXPECT_NEAR(arena->nearest_obstacle(Vec3(0.1, 7.5, 2.5)).distance, 2.5, 1e-12);  // not the wall 0.1 m away
  // nearest_shape() leaves the faces out.
  EXPECT_FALSE(arena->nearest_shape(Vec3(0.1, 7.5, 2.5)).found);
  const Vec3 under_ceiling(3.6, 5, 4.5);
  EXPECT_NEAR(arena->nearest_obstacle(under_ceiling).distance, 0.5, 1e-12);
  EXPECT_NEAR(arena->nearest_shape(under_ceiling).distance, (under_ceiling - Vec3(5, 5, 2.5)).norm() - 1.0,
              std::sqrt(3.0) * 0.3);
  // The faces still enter the octree: the exported tree has the floor and ceiling layers.
  EXPECT_GT(arena->stats().occupied_voxels, 2u * 36u * 36u);
}

TEST(WorldDistanceField, CapAndInside) {
  MapSpec spec = empty_spec(Vec3::Constant(20), 0.25, 2.0);
  spec.spheres.push_back({Vec3(5, 5, 5), 1.0});
  const auto arena = testing::build(spec);
  const Vec3 far(15, 15, 15);
  const NearestObstacle n = arena->nearest_obstacle(far);
  EXPECT_FALSE(n.found);
  EXPECT_EQ(n.distance, 2.0);
  EXPECT_EQ(n.point, far);
  const NearestObstacle inside = arena->nearest_obstacle(Vec3(5.1, 5, 5));
  EXPECT_TRUE(inside.found);
  EXPECT_EQ(inside.distance, 0.0);
  // Outside the arena the nearest grid cell answers.
  EXPECT_TRUE(std::isfinite(arena->nearest_obstacle(Vec3(-50, 5, 5)).distance));
}

TEST(WorldDistanceField, MatchesBruteForceOverOccupiedVoxels) {
  // dynamicEDT3D against an exhaustive search over the occupied voxels: the reported distance is a distance
  // to an occupied voxel (never below the exact minimum) and exceeds it by at most the stated error margin.
  const VoxelGrid g = VoxelGrid::around(Box{Vec3::Zero(), Vec3(6, 5, 4)}, 0.25);
  Occupancy occ(g);
  occ.add_sphere({Vec3(2, 2, 2), 0.7});
  occ.add_cylinder({Vec3(4.4, 3.1, 0), 0.4, 2.5});
  occ.add_sphere({Vec3(5.1, 0.9, 3.2), 0.3});
  const FieldBuild built = build_distance_field(occ, 3.0);
  std::vector<Box> boxes;
  for (int i = 0; i < g.size[0]; ++i)
    for (int j = 0; j < g.size[1]; ++j)
      for (int k = 0; k < g.size[2]; ++k)
        if (occ.occupied(i, j, k)) boxes.push_back({g.cell_lo(i, j, k), g.cell_lo(i, j, k) + Vec3::Constant(g.resolution)});
  EXPECT_EQ(built.occupied_voxels, boxes.size());
  double worst = 0.0;
  for (const Vec3& p : random_points(Box{Vec3::Zero(), Vec3(6, 5, 4)}, 3000, 9)) {
    double t = std::numeric_limits<double>::infinity();
    for (const Box& b : boxes) t = std::min(t, (p - b.clamp(p)).norm());
    const NearestObstacle n = built.field.nearest(p);
    if (t >= 3.0) continue;
    if (!n.found) {
      EXPECT_GE(t, 3.0 - built.field.error_margin());
      continue;
    }
    EXPECT_GE(n.distance, t - 1e-12);
    worst = std::max(worst, n.distance - t);
  }
  EXPECT_LE(worst, built.field.error_margin());
  RecordProperty("worst_excess_m", std::to_string(worst));
}

TEST(WorldDistanceField, ConcurrentQueriesAgree) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.2, 3.0);
  spec.spheres.push_back({Vec3(5, 5, 5), 1.5});
  spec.floor_is_obstacle = true;
  const auto arena = testing::build(spec);
  const auto pts = random_points(arena->bounds(), 20000, 5);
  std::vector<double> reference;
  for (const Vec3& p : pts) reference.push_back(arena->nearest_obstacle(p).distance);
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int rep = 0; rep < 5; ++rep)
        for (std::size_t i = 0; i < pts.size(); ++i) mismatches[std::size_t(t)] += arena->nearest_obstacle(pts[i]).distance != reference[i];
    });
  }
  for (auto& th : threads) th.join();
  for (int m : mismatches) EXPECT_EQ(m, 0);
}

}  // namespace
}  // namespace peg3d::world
