#include "world/moving_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <dynamicEDT3D/dynamicEDTOctomap.h>
#include <octomap/OcTree.h>

#include "world/field/voxel_grid.hpp"

namespace peg3d::world {
namespace {

constexpr int kKeyOffset = 32768;  // OctoMap's key of lattice index n at depth 16: n + 2^15

octomap::point3d to_point(const Vec3& v) {
  return octomap::point3d(static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
}

}  // namespace

struct MovingOccupancyField::Impl {
  VoxelGrid grid;
  double max_distance;
  Occupancy statics;
  octomap::OcTree tree;
  std::unique_ptr<DynamicEDTOctomap> edt;
  std::vector<std::size_t> marked, next;  // grid indices the movers occupy now / at the new time (sorted)

  explicit Impl(const Arena& arena)
      : grid(arena.distance_field().grid()),
        max_distance(arena.max_distance()),
        statics(grid),
        tree(grid.resolution) {
    const MapSpec& spec = arena.map();
    for (const auto& s : spec.spheres) statics.add_sphere(s);
    for (const auto& c : spec.cylinders) statics.add_cylinder(c);
    for (std::size_t i = 0; i < arena.meshes().size(); ++i) statics.add_mesh(arena.meshes()[i], spec.meshes[i].solid_below);
    const float occupied = tree.getClampingThresMaxLog();
    for (int i = 0; i < grid.size[0]; ++i)
      for (int j = 0; j < grid.size[1]; ++j)
        for (int k = 0; k < grid.size[2]; ++k)
          if (statics.occupied(i, j, k)) tree.setNodeValue(key(i, j, k), occupied, true);
    tree.updateInnerOccupancy();
    const float cap = static_cast<float>(max_distance + std::sqrt(3.0) * grid.resolution);
    edt = std::make_unique<DynamicEDTOctomap>(cap, &tree, to_point(grid.cell_center(0, 0, 0)),
                                              to_point(grid.cell_center(grid.size[0] - 1, grid.size[1] - 1, grid.size[2] - 1)),
                                              /*treatUnknownAsOccupied=*/false);
    edt->update(true);
  }

  octomap::OcTreeKey key(int i, int j, int k) const {
    return octomap::OcTreeKey(static_cast<octomap::key_type>(grid.first[0] + i + kKeyOffset),
                              static_cast<octomap::key_type>(grid.first[1] + j + kKeyOffset),
                              static_cast<octomap::key_type>(grid.first[2] + k + kKeyOffset));
  }
  octomap::OcTreeKey key(std::size_t index) const {
    const int k = static_cast<int>(index % std::size_t(grid.size[2]));
    const std::size_t ij = index / std::size_t(grid.size[2]);
    const int j = static_cast<int>(ij % std::size_t(grid.size[1]));
    const int i = static_cast<int>(ij / std::size_t(grid.size[1]));
    return key(i, j, k);
  }
};

MovingOccupancyField::MovingOccupancyField(const Arena& arena) : impl_(std::make_unique<Impl>(arena)) {}
MovingOccupancyField::~MovingOccupancyField() = default;

std::size_t MovingOccupancyField::set_time(const MoverTimeline& movers, double t) {
  Impl& d = *impl_;
  d.next.clear();
  for (int m = 0; m < movers.count(); ++m) {
    for_each_shape_cell(d.grid, movers.mover(m).shape, movers.pose(m, t),
                        [&](int i, int j, int k) { d.next.push_back(d.grid.index(i, j, k)); });
  }
  std::sort(d.next.begin(), d.next.end());
  d.next.erase(std::unique(d.next.begin(), d.next.end()), d.next.end());
  const float occupied = d.tree.getClampingThresMaxLog(), free = d.tree.getClampingThresMinLog();
  const auto is_static = [&](std::size_t index) { return d.statics.cells()[index] != 0; };
  std::size_t changed = 0;
  // Walk both sorted sets: cells only in `marked` are freed, cells only in `next` are marked.
  auto a = d.marked.begin(), b = d.next.begin();
  while (a != d.marked.end() || b != d.next.end()) {
    if (b == d.next.end() || (a != d.marked.end() && *a < *b)) {
      if (!is_static(*a)) d.tree.setNodeValue(d.key(*a), free), ++changed;
      ++a;
    } else if (a == d.marked.end() || *b < *a) {
      if (!is_static(*b)) d.tree.setNodeValue(d.key(*b), occupied), ++changed;
      ++b;
    } else {
      ++a, ++b;
    }
  }
  std::swap(d.marked, d.next);
  d.edt->update(true);
  return changed;
}

NearestObstacle MovingOccupancyField::nearest(const Vec3& p) const {
  const Impl& d = *impl_;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Box box = d.grid.box();
  const Vec3 q = p.cwiseMax(box.lo).cwiseMin(box.hi - Vec3::Constant(1e-9));
  octomap::point3d obstacle(nan, nan, nan);
  float distance = 0.0f;
  d.edt->getDistanceAndClosestObstacle(to_point(q), distance, obstacle);
  if (distance < 0.0f || std::isnan(obstacle.x())) return {d.max_distance, p, false};
  // The obstacle comes back as its voxel's centre: report the voxel box's point nearest to p.
  const double h = 0.5 * d.grid.resolution;
  const Vec3 c(obstacle.x(), obstacle.y(), obstacle.z());
  const Vec3 lo = c - Vec3::Constant(h), hi = c + Vec3::Constant(h);
  const Vec3 nearest = p.cwiseMax(lo).cwiseMin(hi);
  const double dist = (p - nearest).norm();
  if (dist >= d.max_distance) return {d.max_distance, p, false};
  return {dist, nearest, true};
}

}  // namespace peg3d::world
