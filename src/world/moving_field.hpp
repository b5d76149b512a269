#pragma once
// The second way to sense moving obstacles (docs/maps.md compares the two): an OctoMap octree of the map's
// shapes in which the movers' voxels are marked where the movers are, and dynamicEDT3D's distance field kept
// up to date incrementally as they move (what dynamicEDT3D is built for). Each step frees the voxels the
// movers left and marks those they entered; the EDT then propagates only the change.
//
// It is mutable per-run state (one per SimState), and its incremental updates keep history-dependent tie
// breaks between equally near voxels: a run that needs results independent of what ran before rebuilds it
// (the game does, at every reset). The default sensing is exact (MoverTimeline::nearest beside the static
// field): docs/maps.md gives the accuracy and cost of both.

#include <cstddef>
#include <memory>

#include "world/arena.hpp"
#include "world/bodies/mover_timeline.hpp"

namespace peg3d::world {

class MovingOccupancyField {
 public:
  /// The arena's spheres, cylinders and terrain (not its faces) voxelized into a fresh octree and EDT.
  explicit MovingOccupancyField(const Arena& arena);
  ~MovingOccupancyField();
  MovingOccupancyField(const MovingOccupancyField&) = delete;
  MovingOccupancyField& operator=(const MovingOccupancyField&) = delete;

  /// Marks every mover's voxels at time t (conservatively, as Occupancy::add_shape), frees the voxels they
  /// occupied at the previous call and are not static, and updates the EDT. Returns the voxels that changed.
  std::size_t set_time(const MoverTimeline& movers, double t);

  /// The nearest occupied voxel's point nearest to p and its distance, capped at the map's max_distance (as
  /// DistanceField::nearest_shape): within about one voxel diagonal of the exact distance.
  NearestObstacle nearest(const Vec3& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace peg3d::world
