#pragma once
// The read-only distance field queried by the game: for each cell of the VoxelGrid, the nearest occupied cell
// as computed by dynamicEDT3D, stored flat (6 bytes a cell). A query is a table lookup plus a point-to-box
// distance: no allocation, no locking, safe from any number of threads.

#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/vector.hpp"
#include "world/voxel_grid.hpp"

namespace peg3d::world {

/// Answer of a distance query.
struct NearestObstacle {
  double distance = 0.0;        ///< m, from the query point to the nearest occupied voxel, in [0, max_distance]
  Vec3 point = Vec3::Zero();    ///< the point of that voxel nearest to the query (the query point when !found)
  bool found = false;           ///< false when no obstacle lies within max_distance (distance == max_distance)
};

class DistanceField {
 public:
  /// Nearest occupied cell of a cell; x == kNone when there is none within the field's cap.
  struct Cell {
    std::uint16_t x, y, z;
  };
  static constexpr std::uint16_t kNone = 0xFFFF;

  DistanceField() = default;
  DistanceField(const VoxelGrid& grid, double max_distance, std::vector<Cell> cells);

  /// Distance from p to the nearest occupied voxel (its box, not its centre), capped at max_distance, and the
  /// voxel's point nearest to p. Points outside the grid are answered from the nearest grid cell. The voxel
  /// is the one dynamicEDT3D found nearest to the centre of p's cell, so the distance is within about one
  /// voxel diagonal of the exact distance to the occupied voxels.
  NearestObstacle nearest(const Vec3& p) const {
    assert(p.allFinite());
    const Cell c = cells_[grid_.index(cell_of(p, 0), cell_of(p, 1), cell_of(p, 2))];
    if (c.x == kNone) return {max_distance_, p, false};
    const Vec3 lo = grid_.cell_lo(c.x, c.y, c.z);
    const Vec3 q = p.cwiseMax(lo).cwiseMin(lo + Vec3::Constant(grid_.resolution));
    const double d = (p - q).norm();
    if (d >= max_distance_) return {max_distance_, p, false};
    return {d, q, true};
  }

  /// A distance (m) that no obstacle point inside the grid, nor anything outside it, is nearer to p than.
  /// Valid because voxelization is conservative (every obstacle point lies in an occupied voxel): with c the
  /// centre of p's cell and D the EDT's centre-to-centre distance from c, every occupied voxel is at least
  /// D - |p - c| - h from p (h the half diagonal), less the EDT's own error (under one cell).
  double clearance_lower_bound(const Vec3& p) const {
    assert(p.allFinite());
    const int i = cell_of(p, 0), j = cell_of(p, 1), k = cell_of(p, 2);
    const Cell cell = cells_[grid_.index(i, j, k)];
    const Vec3 centre = grid_.cell_center(i, j, k);
    const double centre_distance =
        cell.x == kNone ? max_distance_ : (grid_.cell_center(cell.x, cell.y, cell.z) - centre).norm();
    const double bound = centre_distance - (p - centre).norm() - half_diagonal_ - grid_.resolution;
    return std::min(bound, outer_.inner_distance(p));
  }

  const VoxelGrid& grid() const { return grid_; }
  double max_distance() const { return max_distance_; }
  const std::vector<Cell>& cells() const { return cells_; }
  std::size_t bytes() const { return cells_.size() * sizeof(Cell); }
  /// How much nearest() can exceed the exact distance to the occupied voxels, m: three half diagonals
  /// (cell-centre quantization twice, point-to-box once) plus one cell for the EDT's own approximation.
  double error_margin() const { return 3.0 * half_diagonal_ + grid_.resolution; }

 private:
  /// Index on `axis` of the cell holding p, clamped to the grid. Clamping in floating point first means no
  /// overflow in the conversion, and NaN lands on cell 0.
  int cell_of(const Vec3& p, int axis) const {
    const double n = std::floor(p[axis] * inv_resolution_) - grid_.first[axis];
    return n >= 0.0 ? (n < grid_.size[axis] - 1 ? static_cast<int>(n) : grid_.size[axis] - 1) : 0;
  }

  VoxelGrid grid_;
  Box outer_;
  double inv_resolution_ = 5.0;
  double max_distance_ = 0.0;
  double half_diagonal_ = 0.0;
  std::vector<Cell> cells_;
};

}  // namespace peg3d::world
