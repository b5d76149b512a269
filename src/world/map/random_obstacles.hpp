#pragma once
// Random obstacle generators: rejection sampling with a clearance from agent starts and between obstacles.
// Placement uses std::mt19937_64 and its own uniform mapping (53 random bits per draw), so a seed gives the
// same obstacles with any standard library.

#include <cstdint>
#include <vector>

#include "geometry/vector.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::world {

/// One generator entry of a map.
struct RandomObstacleSpec {
  enum class Kind { kSphere, kCylinder };
  Kind kind = Kind::kSphere;
  int count = 0;                       ///< obstacles to place, >= 0
  double radius_min = 1.0;             ///< m, > 0
  double radius_max = 1.0;             ///< m, >= radius_min
  double height_min = 1.0;             ///< m, > 0 (cylinders only)
  double height_max = 1.0;             ///< m, >= height_min (cylinders only)
  std::uint64_t seed = 0;              ///< seed of this generator's std::mt19937_64
  double clearance_from_starts = 0.0;  ///< m, >= 0: every start point is at least this far from the surface
  double clearance_between = 0.0;      ///< m, >= 0: gap to every obstacle placed before (explicit ones included)
  Box region;                          ///< spheres lie wholly inside; cylinders stand on region.lo.z inside it
  int max_attempts = 1000;             ///< draws per obstacle before giving up, >= 1
};

/// Result of running a generator: as many obstacles as could be placed (fewer than count means failure).
struct RandomObstacles {
  std::vector<SphereObstacle> spheres;
  std::vector<CylinderObstacle> cylinders;
  int placed() const { return static_cast<int>(spheres.size() + cylinders.size()); }
};

/// Places spec.count obstacles one after another; each must keep the clearances against `starts`, the
/// obstacles already in `spheres`/`cylinders`, and the ones placed before it. Stops early when an obstacle
/// cannot be placed within max_attempts draws.
RandomObstacles place_random_obstacles(const RandomObstacleSpec& spec, const std::vector<Vec3>& starts,
                                       const std::vector<SphereObstacle>& spheres,
                                       const std::vector<CylinderObstacle>& cylinders);

}  // namespace peg3d::world
