#include "world/map/random_obstacles.hpp"

#include <type_traits>

#include "core/random.hpp"
#include "world/map/obstacle_geometry.hpp"

namespace peg3d::world {
namespace {

template <class Shape>
bool keeps_clearance(const Shape& shape, const RandomObstacleSpec& spec, const std::vector<Vec3>& starts,
                     const std::vector<SphereObstacle>& spheres, const std::vector<CylinderObstacle>& cylinders) {
  for (const Vec3& s : starts) {
    const double d = signed_distance(s, shape);
    if (d <= 0.0 || d < spec.clearance_from_starts) return false;
  }
  auto apart = [&](double g) { return g > 0.0 && g >= spec.clearance_between; };
  for (const auto& o : spheres) {
    if constexpr (std::is_same_v<Shape, SphereObstacle>) {
      if (!apart(gap(shape, o))) return false;
    } else {
      if (!apart(gap(o, shape))) return false;
    }
  }
  for (const auto& o : cylinders) {
    if (!apart(gap(shape, o))) return false;
  }
  return true;
}

}  // namespace

RandomObstacles place_random_obstacles(const RandomObstacleSpec& spec, const std::vector<Vec3>& starts,
                                       const std::vector<SphereObstacle>& spheres,
                                       const std::vector<CylinderObstacle>& cylinders) {
  Rng rng(spec.seed);
  RandomObstacles out;
  // Everything placed so far, for the clearance between obstacles.
  std::vector<SphereObstacle> all_spheres = spheres;
  std::vector<CylinderObstacle> all_cylinders = cylinders;
  for (int i = 0; i < spec.count; ++i) {
    bool placed = false;
    for (int attempt = 0; attempt < spec.max_attempts && !placed; ++attempt) {
      const double r = uniform(rng, spec.radius_min, spec.radius_max);
      const Box& g = spec.region;
      if (spec.kind == RandomObstacleSpec::Kind::kSphere) {
        const SphereObstacle s{Vec3(uniform(rng, g.lo.x() + r, g.hi.x() - r), uniform(rng, g.lo.y() + r, g.hi.y() - r),
                                    uniform(rng, g.lo.z() + r, g.hi.z() - r)),
                               r};
        if (keeps_clearance(s, spec, starts, all_spheres, all_cylinders)) {
          all_spheres.push_back(s);
          out.spheres.push_back(s);
          placed = true;
        }
      } else {
        const double h = uniform(rng, spec.height_min, spec.height_max);
        const CylinderObstacle c{
            Vec3(uniform(rng, g.lo.x() + r, g.hi.x() - r), uniform(rng, g.lo.y() + r, g.hi.y() - r), g.lo.z()), r, h};
        if (keeps_clearance(c, spec, starts, all_spheres, all_cylinders)) {
          all_cylinders.push_back(c);
          out.cylinders.push_back(c);
          placed = true;
        }
      }
    }
    if (!placed) break;
  }
  return out;
}

}  // namespace peg3d::world
