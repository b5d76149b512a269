#pragma once
// The voxel lattice shared by the octree, the occupancy and the distance field. Cells are OctoMap's
// max-depth voxels: cell n on an axis spans [n * res, (n + 1) * res), n = floor(coordinate / res), so grid
// cells and octree keys coincide (key = n + 32768).

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/pose.hpp"
#include "geometry/vector.hpp"
#include "world/map/map_spec.hpp"
#include "world/map/triangle_mesh.hpp"

namespace peg3d::world {

/// A box of cells: the arena's cells plus one layer outside each face (where boundary faces are voxelized).
struct VoxelGrid {
  double resolution = 0.2;               ///< m, cell edge
  std::array<int, 3> first{0, 0, 0};     ///< lattice index n of the grid's cell 0 on each axis
  std::array<int, 3> size{0, 0, 0};      ///< cells on each axis

  /// The arena's cells and one cell of padding around them.
  static VoxelGrid around(const Box& arena, double resolution);

  std::size_t cell_count() const { return std::size_t(size[0]) * std::size_t(size[1]) * std::size_t(size[2]); }
  /// Linear index, z fastest (the layout of DynamicEDT3D's arrays, so copying its answers streams).
  std::size_t index(int i, int j, int k) const {
    return (std::size_t(i) * std::size_t(size[1]) + std::size_t(j)) * std::size_t(size[2]) + std::size_t(k);
  }
  /// Lower corner of cell (i, j, k), m.
  Vec3 cell_lo(int i, int j, int k) const {
    return Vec3(first[0] + i, first[1] + j, first[2] + k) * resolution;
  }
  Vec3 cell_center(int i, int j, int k) const { return cell_lo(i, j, k) + Vec3::Constant(0.5 * resolution); }
  /// The box covered by all cells.
  Box box() const {
    return {cell_lo(0, 0, 0), cell_lo(size[0], size[1], size[2])};
  }
  /// Index along `axis` of the cell holding coordinate c (may be outside [0, size)), like OctoMap's coordToKey.
  int axis_cell(double c, int axis) const { return static_cast<int>(std::floor(c * (1.0 / resolution))) - first[axis]; }
};

/// A dense occupancy bitmap over a VoxelGrid. A cell is occupied when its closed box meets the shape
/// (conservative voxelization), so every point of an obstacle lies in an occupied cell.
class Occupancy {
 public:
  explicit Occupancy(const VoxelGrid& grid) : grid_(grid), occupied_(grid.cell_count(), 0) {}

  void add_sphere(const SphereObstacle& s);
  void add_cylinder(const CylinderObstacle& c);
  /// The mesh's triangles; with solid_below also every cell under the mesh's highest surface cell of each
  /// column, down to the grid's bottom.
  void add_mesh(const TriangleMesh& mesh, bool solid_below);
  /// A posed convex shape (a mover at some instant): every cell whose centre lies within half a cell diagonal of
  /// the shape (conservative: every point of the shape is in a marked cell).
  void add_shape(const Shape& shape, const Pose& pose);
  /// The padding layer outside the chosen faces of the arena (see for_each_boundary_cell).
  void add_boundary(bool floor, bool ceiling, bool walls);

  bool occupied(int i, int j, int k) const { return occupied_[grid_.index(i, j, k)] != 0; }
  std::size_t occupied_count() const;
  const VoxelGrid& grid() const { return grid_; }
  const std::vector<std::uint8_t>& cells() const { return occupied_; }

 private:
  void set(int i, int j, int k) { occupied_[grid_.index(i, j, k)] = 1; }
  /// Cell index range [lo, hi] on each axis covering [a, b], clipped to the grid; false if empty.
  bool cell_range(const Vec3& a, const Vec3& b, std::array<int, 3>& lo, std::array<int, 3>& hi) const;

  VoxelGrid grid_;
  std::vector<std::uint8_t> occupied_;
};

/// Calls f(i, j, k) for each cell of the padding layers outside the chosen faces of the arena: the voxels that
/// stand for the floor (k = 0), the ceiling (k = last) and the walls (i or j first or last).
template <class F>
void for_each_boundary_cell(const VoxelGrid& grid, bool floor, bool ceiling, bool walls, F&& f) {
  const auto [nx, ny, nz] = grid.size;
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const bool wall_column = walls && (i == 0 || i == nx - 1 || j == 0 || j == ny - 1);
      for (int k = 0; k < nz; ++k) {
        if (wall_column || (floor && k == 0) || (ceiling && k == nz - 1)) f(i, j, k);
      }
    }
  }
}

/// Calls f(i, j, k) for each grid cell whose centre lies within half a cell diagonal of the posed shape
/// (Occupancy::add_shape's cells).
template <class F>
void for_each_shape_cell(const VoxelGrid& grid, const Shape& shape, const Pose& pose, F&& f) {
  const double h = 0.5 * std::sqrt(3.0) * grid.resolution;
  const double reach = shape.bounding_radius() + h;
  std::array<int, 3> lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(0, grid.axis_cell(pose.position[a] - reach, a));
    hi[a] = std::min(grid.size[a] - 1, grid.axis_cell(pose.position[a] + reach, a));
    if (lo[a] > hi[a]) return;
  }
  for (int i = lo[0]; i <= hi[0]; ++i) {
    for (int j = lo[1]; j <= hi[1]; ++j) {
      for (int k = lo[2]; k <= hi[2]; ++k) {
        if (nearest_on_shape(shape, pose, grid.cell_center(i, j, k)).distance <= h) f(i, j, k);
      }
    }
  }
}

/// Separating-axis test of a triangle against an axis-aligned box (centre, half extents); touching counts.
bool triangle_overlaps_box(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& box_center,
                           const Vec3& box_half);

}  // namespace peg3d::world
