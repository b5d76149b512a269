// Voxelization: the lattice matches OctoMap's keys, and every shape occupies exactly the cells its closed box
// meets (conservative, so the distance field never overestimates clearance), no more.

#include <random>

#include <gtest/gtest.h>

#include "world/map/obstacle_geometry.hpp"
#include "world/map/triangle_mesh.hpp"
#include "world/field/voxel_grid.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

TEST(WorldVoxelGrid, PaperArenaAtFiveCentimetreMultiples) {
  const Box arena{Vec3::Zero(), Vec3(35, 35, 20)};
  for (const auto& [res, n] : std::vector<std::pair<double, std::array<int, 3>>>{
           {0.1, {350, 350, 200}}, {0.2, {175, 175, 100}}, {0.25, {140, 140, 80}}}) {
    const VoxelGrid g = VoxelGrid::around(arena, res);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(g.first[a], -1) << res;
      EXPECT_EQ(g.size[a], n[a] + 2) << res;  // one padding cell each side
    }
    EXPECT_NEAR(g.box().lo.x(), -res, 1e-12);
    EXPECT_NEAR(g.box().hi.z(), 20 + res, 1e-9);
  }
}

TEST(WorldVoxelGrid, CellsAreOctomapVoxels) {
  const VoxelGrid g = VoxelGrid::around(Box{Vec3(-3, -3, -3), Vec3(3, 3, 3)}, 0.5);
  // OctoMap: voxel n spans [n res, (n + 1) res); -0.1 lies in voxel -1, 0 in voxel 0.
  EXPECT_EQ(g.axis_cell(-0.1, 0) + g.first[0], -1);
  EXPECT_EQ(g.axis_cell(0.0, 0) + g.first[0], 0);
  EXPECT_EQ(g.cell_center(-g.first[0], 0, 0).x(), 0.25);
}

TEST(WorldVoxelGrid, TriangleBoxOverlap) {
  const Vec3 c = Vec3::Zero(), h = Vec3::Constant(0.5);
  // Crossing the box, touching a face, just beyond a face, and separated only by an edge-cross axis.
  EXPECT_TRUE(triangle_overlaps_box(Vec3(-2, -2, 0), Vec3(2, -2, 0), Vec3(0, 2, 0), c, h));
  EXPECT_TRUE(triangle_overlaps_box(Vec3(0.5, -1, -1), Vec3(0.5, 1, -1), Vec3(0.5, 0, 1), c, h));
  EXPECT_FALSE(triangle_overlaps_box(Vec3(0.51, -1, -1), Vec3(0.51, 1, -1), Vec3(0.51, 0, 1), c, h));
  // A triangle near a box corner whose AABB overlaps the box but whose plane passes beyond the corner.
  EXPECT_FALSE(triangle_overlaps_box(Vec3(1.2, 0.4, 0.4), Vec3(0.4, 1.2, 0.4), Vec3(0.4, 0.4, 1.2), c, h));
  EXPECT_TRUE(triangle_overlaps_box(Vec3(0.8, 0.3, 0.3), Vec3(0.3, 0.8, 0.3), Vec3(0.3, 0.3, 0.8), c, h));
}

/// Distance from p to the closed box of cell (i, j, k).
double cell_distance(const VoxelGrid& g, int i, int j, int k, const Vec3& p) {
  const Vec3 lo = g.cell_lo(i, j, k);
  return (p - p.cwiseMax(lo).cwiseMin(lo + Vec3::Constant(g.resolution))).norm();
}

TEST(WorldVoxelGrid, SphereOccupiesExactlyTheCellsItMeets) {
  const VoxelGrid g = VoxelGrid::around(Box{Vec3::Zero(), Vec3::Constant(6)}, 0.25);
  const SphereObstacle s{Vec3(3.1, 2.9, 3.05), 1.3};
  Occupancy occ(g);
  occ.add_sphere(s);
  for (int i = 0; i < g.size[0]; ++i)
    for (int j = 0; j < g.size[1]; ++j)
      for (int k = 0; k < g.size[2]; ++k) {
        const double d = cell_distance(g, i, j, k, s.center);
        if (d < s.radius - 1e-9) {
          EXPECT_TRUE(occ.occupied(i, j, k));
        } else if (d > s.radius + 1e-9) {
          EXPECT_FALSE(occ.occupied(i, j, k));
        }
      }
}

TEST(WorldVoxelGrid, CylinderOccupiesExactlyTheCellsItMeets) {
  const VoxelGrid g = VoxelGrid::around(Box{Vec3::Zero(), Vec3::Constant(6)}, 0.25);
  const CylinderObstacle c{Vec3(2.9, 3.2, 1.1), 0.9, 2.3};
  Occupancy occ(g);
  occ.add_cylinder(c);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Every point of the cylinder lies in an occupied cell...
  for (int n = 0; n < 20000; ++n) {
    const double r = c.radius * std::sqrt(u(rng)), a = 2 * kPi * u(rng);
    const Vec3 p = c.base + Vec3(r * std::cos(a), r * std::sin(a), c.height * u(rng));
    EXPECT_TRUE(occ.occupied(g.axis_cell(p.x(), 0), g.axis_cell(p.y(), 1), g.axis_cell(p.z(), 2)));
  }
  // ...and every occupied cell meets it: its x-y square reaches the disc and its z range the cylinder's.
  for (int i = 0; i < g.size[0]; ++i)
    for (int j = 0; j < g.size[1]; ++j)
      for (int k = 0; k < g.size[2]; ++k) {
        if (!occ.occupied(i, j, k)) continue;
        const Vec3 lo = g.cell_lo(i, j, k), hi = lo + Vec3::Constant(g.resolution);
        const Vec3 q = c.base.cwiseMax(lo).cwiseMin(hi);
        EXPECT_LE(std::hypot(q.x() - c.base.x(), q.y() - c.base.y()), c.radius + 1e-9);
        EXPECT_LE(lo.z(), c.base.z() + c.height + 1e-9);
        EXPECT_GE(hi.z(), c.base.z() - 1e-9);
      }
}

TEST(WorldVoxelGrid, MeshSurfaceCellsCoverEveryTrianglePoint) {
  const VoxelGrid g = VoxelGrid::around(Box{Vec3(-3, -6, -1), Vec3(3, 6, 11)}, 0.2);
  TriangleMesh wall = import_mesh(testing::mesh_path("wall.obj"));
  transform_mesh(wall, 1.0, Vec3(0, 0, 20), Vec3(0.05, 0, 0));  // slanted, off the lattice
  Occupancy occ(g);
  occ.add_mesh(wall, false);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const auto& f : wall.faces) {
    for (int n = 0; n < 5000; ++n) {
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Vec3 p = wall.vertices[f[0]] + a * (wall.vertices[f[1]] - wall.vertices[f[0]]) +
                     b * (wall.vertices[f[2]] - wall.vertices[f[0]]);
      EXPECT_TRUE(occ.occupied(g.axis_cell(p.x(), 0), g.axis_cell(p.y(), 1), g.axis_cell(p.z(), 2)));
    }
  }
  // A surface, not a slab: cells two voxels off the plane stay free.
  const Vec3 n = (wall.vertices[1] - wall.vertices[0]).cross(wall.vertices[2] - wall.vertices[0]).normalized();
  const Vec3 off = Vec3(0.05, 0, 5) + 2.0 * g.resolution * std::sqrt(3.0) * n;
  EXPECT_FALSE(occ.occupied(g.axis_cell(off.x(), 0), g.axis_cell(off.y(), 1), g.axis_cell(off.z(), 2)));
}

TEST(WorldVoxelGrid, SolidBelowFillsUnderTheSurface) {
  const VoxelGrid g = VoxelGrid::around(Box{Vec3::Zero(), Vec3(20, 10, 6)}, 0.25);
  const TriangleMesh ridge = import_mesh(testing::mesh_path("ridge.obj"));
  Occupancy surface(g), solid(g);
  surface.add_mesh(ridge, false);
  solid.add_mesh(ridge, true);
  auto cell = [&](const Occupancy& o, const Vec3& p) {
    return o.occupied(g.axis_cell(p.x(), 0), g.axis_cell(p.y(), 1), g.axis_cell(p.z(), 2));
  };
  EXPECT_FALSE(cell(surface, Vec3(10, 5, 2)));  // inside the ridge
  EXPECT_TRUE(cell(solid, Vec3(10, 5, 2)));
  EXPECT_TRUE(cell(solid, Vec3(10, 5, 3.9)));
  EXPECT_FALSE(cell(solid, Vec3(10, 5, 4.5)));  // above its top
  EXPECT_FALSE(cell(solid, Vec3(3, 5, 0.5)));   // above the flat part
  EXPECT_TRUE(cell(solid, Vec3(3, 5, -0.1)));   // below it, in the padding layer
}

TEST(WorldVoxelGrid, BoundaryFacesFillThePaddingLayers) {
  const VoxelGrid g = VoxelGrid::around(Box{Vec3::Zero(), Vec3(2, 2, 2)}, 0.5);
  Occupancy floor_only(g), walls_only(g);
  floor_only.add_boundary(true, false, false);
  walls_only.add_boundary(false, false, true);
  EXPECT_EQ(floor_only.occupied_count(), std::size_t(6 * 6));
  EXPECT_TRUE(floor_only.occupied(3, 3, 0));
  EXPECT_FALSE(floor_only.occupied(3, 3, 5));
  EXPECT_EQ(walls_only.occupied_count(), std::size_t((6 * 6 - 4 * 4) * 6));
  EXPECT_TRUE(walls_only.occupied(0, 3, 3));
  EXPECT_FALSE(walls_only.occupied(1, 3, 3));
}

}  // namespace
}  // namespace peg3d::world
