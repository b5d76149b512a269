#pragma once
// The read-only distance field queried by the game. Obstacles (spheres, cylinders, meshes): for each cell of
// the VoxelGrid, the nearest occupied cell as computed by dynamicEDT3D, stored flat (6 bytes a cell).
// Arena faces that count as obstacles: exact planes, evaluated per query (they are in the octree too, for
// export, but the EDT does not need them and the collision early-out must not see them). A query is a table
// lookup, a point-to-box distance and up to six plane distances: no allocation, no locking, any thread.

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/vector.hpp"
#include "world/field/voxel_grid.hpp"

namespace peg3d::world {

/// Answer of a distance query.
struct NearestObstacle {
  double distance = 0.0;        ///< m, from the query point to the nearest obstacle, in [0, max_distance]
  Vec3 point = Vec3::Zero();    ///< the obstacle's point nearest to the query (the query point when !found)
  bool found = false;           ///< false when no obstacle lies within max_distance (distance == max_distance)
};

/// Which faces of the arena box are obstacles.
struct ArenaFaces {
  bool floor = false;    ///< z = lo.z
  bool ceiling = false;  ///< z = hi.z
  bool walls = false;    ///< x = lo.x, x = hi.x, y = lo.y, y = hi.y
};

class DistanceField {
 public:
  /// Nearest occupied cell of a cell; x == kNone when there is none within the field's cap.
  struct Cell {
    std::uint16_t x, y, z;
  };
  static constexpr std::uint16_t kNone = 0xFFFF;

  DistanceField() = default;
  DistanceField(const VoxelGrid& grid, double max_distance, std::vector<Cell> cells, const Box& arena = {},
                ArenaFaces faces = {});

  /// Distance from p to the nearest obstacle, capped at max_distance, and the obstacle's point nearest to p.
  /// For shapes that is the nearest occupied voxel (its box, not its centre) that dynamicEDT3D found for the
  /// centre of p's cell: within about one voxel diagonal of the exact distance. For faces it is exact: the
  /// obstacle is the half-space beyond the face. Points outside the grid use the nearest grid cell.
  NearestObstacle nearest(const Vec3& p) const {
    NearestObstacle best = nearest_shape(p);
    if (any_face_) {
      // Distance to the half-space beyond each face; outside the arena it is 0 and the point is p itself.
      auto face = [&](bool on, int axis, double plane, double sign) {
        if (!on) return;
        const double d = std::max(sign * (p[axis] - plane), 0.0);
        if (d >= best.distance) return;
        Vec3 q = p;
        if (d > 0.0) q[axis] = plane;
        best = {d, q, true};
      };
      face(faces_.floor, 2, arena_.lo.z(), 1.0);
      face(faces_.ceiling, 2, arena_.hi.z(), -1.0);
      face(faces_.walls, 0, arena_.lo.x(), 1.0);
      face(faces_.walls, 0, arena_.hi.x(), -1.0);
      face(faces_.walls, 1, arena_.lo.y(), 1.0);
      face(faces_.walls, 1, arena_.hi.y(), -1.0);
    }
    return best;
  }

  /// nearest() without the arena faces: the nearest occupied voxel of a sphere, cylinder or mesh.
  NearestObstacle nearest_shape(const Vec3& p) const {
    assert(p.allFinite());
    const Cell c = cells_[grid_.index(cell_of(p, 0), cell_of(p, 1), cell_of(p, 2))];
    if (c.x == kNone) return {max_distance_, p, false};
    const Vec3 lo = grid_.cell_lo(c.x, c.y, c.z);
    const Vec3 q = p.cwiseMax(lo).cwiseMin(lo + Vec3::Constant(grid_.resolution));
    const double d = (p - q).norm();
    if (d >= max_distance_) return {max_distance_, p, false};
    return {d, q, true};
  }

  /// A distance (m) that no obstacle point of a sphere, cylinder or mesh (inside the grid or outside it) is
  /// nearer to p than; arena faces do not count. Valid because voxelization is conservative (every obstacle
  /// point lies in an occupied voxel): with c the centre of p's cell and D the EDT's centre-to-centre distance
  /// from c, every occupied voxel is at least D - |p - c| - h from p (h the half diagonal), less the EDT's own
  /// error (under one cell).
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
  /// Index on `axis` of the cell holding p, clamped to the grid. Clamped in floating point, so the conversion
  /// cannot overflow, truncation equals floor (the value is >= 0), and NaN lands on cell 0. (std::floor is a
  /// library call without SSE4.1.)
  int cell_of(const Vec3& p, int axis) const {
    const double n = p[axis] * inv_resolution_ - grid_.first[axis];
    return n >= 0.0 ? (n < grid_.size[axis] ? static_cast<int>(n) : grid_.size[axis] - 1) : 0;
  }

  VoxelGrid grid_;
  Box outer_;
  Box arena_;
  ArenaFaces faces_;
  bool any_face_ = false;
  double inv_resolution_ = 5.0;
  double max_distance_ = 0.0;
  double half_diagonal_ = 0.0;
  std::vector<Cell> cells_;
};

}  // namespace peg3d::world
