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
    const Cell c = cells_[cell_index(p)];
    if (c.x == kNone) return {max_distance_, p, false};
    const Vec3 lo = Vec3(grid_.first[0] + c.x, grid_.first[1] + c.y, grid_.first[2] + c.z) * grid_.resolution;
    const Vec3 q = p.cwiseMax(lo).cwiseMin(lo + Vec3::Constant(grid_.resolution));
    const double d = (p - q).norm();
    if (d >= max_distance_) return {max_distance_, p, false};
    return {d, q, true};
  }

  /// A distance (m) that no obstacle point inside the grid, nor anything outside it, is nearer to p than:
  /// the field's answer minus its worst-case error, and at most p's distance to the grid's faces.
  /// Valid because voxelization is conservative (every obstacle point lies in an occupied voxel).
  double clearance_lower_bound(const Vec3& p) const {
    const double to_edge = outer_.inner_distance(p);
    return std::min(nearest(p).distance - error_margin_, to_edge);
  }

  const VoxelGrid& grid() const { return grid_; }
  double max_distance() const { return max_distance_; }
  const std::vector<Cell>& cells() const { return cells_; }
  std::size_t bytes() const { return cells_.size() * sizeof(Cell); }
  /// The answer's worst-case underestimate of the distance to the nearest obstacle point, m.
  double error_margin() const { return error_margin_; }

 private:
  std::size_t cell_index(const Vec3& p) const {
    int idx[3];
    for (int a = 0; a < 3; ++a) {
      // Clamp in floating point first: no overflow in the conversion, and NaN lands on cell 0.
      const double n = std::floor(p[a] * inv_resolution_) - grid_.first[a];
      idx[a] = n >= 0.0 ? (n < grid_.size[a] - 1 ? static_cast<int>(n) : grid_.size[a] - 1) : 0;
    }
    return grid_.index(idx[0], idx[1], idx[2]);
  }

  VoxelGrid grid_;
  Box outer_;
  double inv_resolution_ = 5.0;
  double max_distance_ = 0.0;
  double error_margin_ = 0.0;
  std::vector<Cell> cells_;
};

}  // namespace peg3d::world
