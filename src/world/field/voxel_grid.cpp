#include "world/field/voxel_grid.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

namespace peg3d::world {
namespace {

/// floor(x), except that values within rounding noise of an integer snap to it: an arena side of 35 m at
/// 0.1 m must give exactly 350 cells, not 351.
long snapped_floor(double x) {
  const double r = std::round(x);
  return std::abs(x - r) <= 1e-9 * std::max(1.0, std::abs(x)) ? static_cast<long>(r) : static_cast<long>(std::floor(x));
}

// Small margins make the tests conservative against rounding: a shape touching a cell face occupies the cell.
constexpr double kRelativeSlack = 1e-9;

}  // namespace

VoxelGrid VoxelGrid::around(const Box& arena, double resolution) {
  VoxelGrid g;
  g.resolution = resolution;
  const double inv = 1.0 / resolution;
  for (int a = 0; a < 3; ++a) {
    const long lo = snapped_floor(arena.lo[a] * inv);
    const double top = arena.hi[a] * inv;
    const double top_rounded = std::round(top);
    // The last cell is the one holding points just below hi: when hi lies on a cell face, the cell below it.
    const long hi = std::abs(top - top_rounded) <= 1e-9 * std::max(1.0, std::abs(top))
                        ? static_cast<long>(top_rounded) - 1
                        : static_cast<long>(std::floor(top));
    g.first[a] = static_cast<int>(lo - 1);
    g.size[a] = static_cast<int>(std::max(hi, lo) - lo + 3);
  }
  return g;
}

bool Occupancy::cell_range(const Vec3& a, const Vec3& b, std::array<int, 3>& lo, std::array<int, 3>& hi) const {
  const double slack = kRelativeSlack * grid_.resolution;
  for (int k = 0; k < 3; ++k) {
    // Cells whose closed box meets [a, b]: a cell face lying exactly on a or b counts.
    lo[k] = std::max(0, grid_.axis_cell(a[k] - slack, k));
    hi[k] = std::min(grid_.size[k] - 1, grid_.axis_cell(b[k] + slack, k));
    if (lo[k] > hi[k]) return false;
  }
  return true;
}

void Occupancy::add_sphere(const SphereObstacle& s) {
  std::array<int, 3> lo, hi;
  if (!cell_range(s.center.array() - s.radius, s.center.array() + s.radius, lo, hi)) return;
  const double r = s.radius + kRelativeSlack * grid_.resolution;
  for (int i = lo[0]; i <= hi[0]; ++i) {
    for (int j = lo[1]; j <= hi[1]; ++j) {
      for (int k = lo[2]; k <= hi[2]; ++k) {
        const Vec3 c0 = grid_.cell_lo(i, j, k);
        const Vec3 nearest = s.center.cwiseMax(c0).cwiseMin(c0 + Vec3::Constant(grid_.resolution));
        if ((nearest - s.center).squaredNorm() <= r * r) set(i, j, k);
      }
    }
  }
}

void Occupancy::add_shape(const Shape& shape, const Pose& pose) {
  for_each_shape_cell(grid_, shape, pose, [&](int i, int j, int k) { set(i, j, k); });
}

void Occupancy::add_cylinder(const CylinderObstacle& c) {
  std::array<int, 3> lo, hi;
  const Vec3 a(c.base.x() - c.radius, c.base.y() - c.radius, c.base.z());
  const Vec3 b(c.base.x() + c.radius, c.base.y() + c.radius, c.base.z() + c.height);
  if (!cell_range(a, b, lo, hi)) return;
  const double r = c.radius + kRelativeSlack * grid_.resolution;
  for (int j = lo[1]; j <= hi[1]; ++j) {
    for (int i = lo[0]; i <= hi[0]; ++i) {
      // The cylinder meets a cell when its disc meets the cell's x-y square and the z ranges overlap;
      // cell_range already clipped z.
      const Vec3 c0 = grid_.cell_lo(i, j, 0);
      const double nx = std::clamp(c.base.x(), c0.x(), c0.x() + grid_.resolution);
      const double ny = std::clamp(c.base.y(), c0.y(), c0.y() + grid_.resolution);
      const double dx = nx - c.base.x(), dy = ny - c.base.y();
      if (dx * dx + dy * dy > r * r) continue;
      for (int k = lo[2]; k <= hi[2]; ++k) set(i, j, k);
    }
  }
}

bool triangle_overlaps_box(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& box_center, const Vec3& box_half) {
  const Vec3 v[3] = {a - box_center, b - box_center, c - box_center};
  // Axes 1-3: the box's face normals.
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({v[0][k], v[1][k], v[2][k]});
    const double hi = std::max({v[0][k], v[1][k], v[2][k]});
    if (lo > box_half[k] || hi < -box_half[k]) return false;
  }
  // Axis 4: the triangle's normal.
  const Vec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  const Vec3 n = e[0].cross(e[1]);
  if (std::abs(n.dot(v[0])) > box_half.dot(n.cwiseAbs())) return false;
  // Axes 5-13: each box axis crossed with each edge. A zero axis (edge parallel to a box axis) never
  // separates, which keeps the test conservative.
  for (const Vec3& edge : e) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 axis = Vec3::Unit(k).cross(edge);
      const double p0 = axis.dot(v[0]), p1 = axis.dot(v[1]), p2 = axis.dot(v[2]);
      const double r = box_half.dot(axis.cwiseAbs());
      if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
    }
  }
  return true;
}

void Occupancy::add_mesh(const TriangleMesh& mesh, bool solid_below) {
  const double res = grid_.resolution;
  const Vec3 half = Vec3::Constant(0.5 * res * (1.0 + 1e-6));
  // Highest surface cell of each column, for solid_below.
  std::vector<int> top;
  if (solid_below) top.assign(std::size_t(grid_.size[0]) * std::size_t(grid_.size[1]), -1);
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3& b = mesh.vertices[f[1]];
    const Vec3& c = mesh.vertices[f[2]];
    std::array<int, 3> lo, hi;
    if (!cell_range(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), lo, hi)) continue;
    const Vec3 n = (b - a).cross(c - a);
    const bool steep = std::abs(n.z()) <= 1e-6 * n.norm();
    for (int j = lo[1]; j <= hi[1]; ++j) {
      for (int i = lo[0]; i <= hi[0]; ++i) {
        int k0 = lo[2], k1 = hi[2];
        if (!steep) {
          // Only the cells the triangle's plane crosses within this column can meet the triangle.
          const Vec3 c0 = grid_.cell_lo(i, j, 0);
          double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
          for (int corner = 0; corner < 4; ++corner) {
            const double x = c0.x() + ((corner & 1) != 0 ? res : 0.0);
            const double y = c0.y() + ((corner & 2) != 0 ? res : 0.0);
            const double z = a.z() - (n.x() * (x - a.x()) + n.y() * (y - a.y())) / n.z();
            zmin = std::min(zmin, z);
            zmax = std::max(zmax, z);
          }
          k0 = std::max(k0, grid_.axis_cell(zmin - res * kRelativeSlack, 2));
          k1 = std::min(k1, grid_.axis_cell(zmax + res * kRelativeSlack, 2));
        }
        for (int k = k0; k <= k1; ++k) {
          if (!triangle_overlaps_box(a, b, c, grid_.cell_center(i, j, k), half)) continue;
          set(i, j, k);
          if (solid_below) {
            int& t = top[std::size_t(j) * std::size_t(grid_.size[0]) + std::size_t(i)];
            t = std::max(t, k);
          }
        }
      }
    }
  }
  if (!solid_below) return;
  for (int j = 0; j < grid_.size[1]; ++j) {
    for (int i = 0; i < grid_.size[0]; ++i) {
      const int t = top[std::size_t(j) * std::size_t(grid_.size[0]) + std::size_t(i)];
      for (int k = 0; k < t; ++k) set(i, j, k);
    }
  }
}

void Occupancy::add_boundary(bool floor, bool ceiling, bool walls) {
  for_each_boundary_cell(grid_, floor, ceiling, walls, [this](int i, int j, int k) { set(i, j, k); });
}

std::size_t Occupancy::occupied_count() const {
  return static_cast<std::size_t>(std::count(occupied_.begin(), occupied_.end(), std::uint8_t{1}));
}

}  // namespace peg3d::world
