#include "world/field/field_builder.hpp"

#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <dynamicEDT3D/dynamicEDTOctomap.h>
#include <fmt/format.h>
#include <octomap/OcTree.h>

namespace peg3d::world {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// OctoMap's key of lattice index n at the maximum depth (16): n + 2^15.
constexpr int kKeyOffset = 32768;

}  // namespace

DistanceField::DistanceField(const VoxelGrid& grid, double max_distance, std::vector<Cell> cells, const Box& arena,
                             ArenaFaces faces)
    : grid_(grid),
      outer_(grid.box()),
      arena_(arena),
      faces_(faces),
      any_face_(faces.floor || faces.ceiling || faces.walls),
      inv_resolution_(1.0 / grid.resolution),
      max_distance_(max_distance),
      half_diagonal_(0.5 * std::sqrt(3.0) * grid.resolution),
      cells_(std::move(cells)) {
  if (cells_.size() != grid.cell_count()) throw std::invalid_argument("DistanceField: cell count does not match grid");
}

std::size_t estimate_build_bytes(const VoxelGrid& grid) {
  const std::size_t cells = grid.cell_count();
  // DynamicEDT3D: 24-byte dataCell per cell plus one pointer per (x, y) row and per x slice.
  const std::size_t edt = cells * 24 + std::size_t(grid.size[0]) * std::size_t(grid.size[1]) * sizeof(void*) +
                          std::size_t(grid.size[0]) * sizeof(void*);
  return edt + cells * (1 + sizeof(DistanceField::Cell));
}

namespace {

std::string serialize(octomap::OcTree& tree) {
  // OctoMap's .bt layout: a text header, then the tree's data. Written here rather than with writeBinary(),
  // whose Debian build prints " done." on stderr for every tree.
  tree.updateInnerOccupancy();
  tree.toMaxLikelihood();
  tree.prune();
  std::ostringstream bt;
  bt << fmt::format("# Octomap OcTree binary file\n# written by peg3d\n#\nid {}\nsize {}\nres {}\ndata\n",
                    tree.getTreeType(), tree.size(), tree.getResolution());
  tree.writeBinaryData(bt);
  if (!bt) throw std::runtime_error("cannot serialize the octree");
  return std::move(bt).str();
}

}  // namespace

std::string octree_with_shapes(const std::string& octree_bt, const VoxelGrid& g,
                               const std::vector<std::pair<Shape, Pose>>& shapes) {
  std::istringstream in(octree_bt);
  octomap::OcTree tree(g.resolution);
  if (!tree.readBinary(in)) throw std::runtime_error("cannot read the world's octree");
  const float occupied = tree.getClampingThresMaxLog();
  for (const auto& [shape, pose] : shapes) {
    for_each_shape_cell(g, shape, pose, [&](int i, int j, int k) {
      const octomap::OcTreeKey key(static_cast<octomap::key_type>(g.first[0] + i + kKeyOffset),
                                   static_cast<octomap::key_type>(g.first[1] + j + kKeyOffset),
                                   static_cast<octomap::key_type>(g.first[2] + k + kKeyOffset));
      tree.setNodeValue(key, occupied, /*lazy_eval=*/true);
    });
  }
  return serialize(tree);
}

namespace {

// Each grid cell's nearest occupied voxel, from dynamicEDT3D over `tree` (the voxels' indices; kNone where
// none lies within the cap).
std::vector<DistanceField::Cell> nearest_voxels(octomap::OcTree& tree, const VoxelGrid& g, double max_distance) {
  auto to_point = [](const Vec3& v) {
    return octomap::point3d(static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
  };
  const octomap::point3d bbx_min = to_point(g.cell_center(0, 0, 0));
  const octomap::point3d bbx_max = to_point(g.cell_center(g.size[0] - 1, g.size[1] - 1, g.size[2] - 1));
  // One voxel diagonal beyond the cap: the compact field reports distances from a point to voxel boxes, which
  // are at most a diagonal shorter than the centre-to-centre distances the EDT propagates.
  const float edt_cap = static_cast<float>(max_distance + std::sqrt(3.0) * g.resolution);
  std::vector<DistanceField::Cell> cells(g.cell_count());
  DynamicEDTOctomap edt(edt_cap, &tree, bbx_min, bbx_max, /*treatUnknownAsOccupied=*/false);
  edt.update(/*updateRealDist=*/true);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const double inv = 1.0 / g.resolution;
  std::size_t n = 0;
  for (int i = 0; i < g.size[0]; ++i) {
    for (int j = 0; j < g.size[1]; ++j) {
      for (int k = 0; k < g.size[2]; ++k, ++n) {
        const octomap::point3d p = to_point(g.cell_center(i, j, k));
        // The EDT leaves the obstacle unwritten when it found none within the cap.
        octomap::point3d obstacle(nan, nan, nan);
        float distance = 0.0f;
        edt.getDistanceAndClosestObstacle(p, distance, obstacle);
        if (distance < 0.0f || std::isnan(obstacle.x())) {
          cells[n] = {DistanceField::kNone, DistanceField::kNone, DistanceField::kNone};
          continue;
        }
        // The obstacle comes back as its voxel centre (float): half a cell from any face, so floor is exact.
        int idx[3];
        for (int a = 0; a < 3; ++a) {
          idx[a] = static_cast<int>(std::floor(double(obstacle(a)) * inv)) - g.first[a];
          assert(idx[a] >= 0 && idx[a] < g.size[a]);
        }
        cells[n] = {static_cast<std::uint16_t>(idx[0]), static_cast<std::uint16_t>(idx[1]),
                    static_cast<std::uint16_t>(idx[2])};
      }
    }
  }
  return cells;
}

}  // namespace

FieldBuild build_distance_field(const Occupancy& occupancy, double max_distance, const Box& arena, ArenaFaces faces) {
  const VoxelGrid& g = occupancy.grid();
  FieldBuild out;
  auto t0 = std::chrono::steady_clock::now();

  octomap::OcTree tree(g.resolution);
  const float occupied = tree.getClampingThresMaxLog();
  auto set_occupied = [&](int i, int j, int k) {
    const octomap::OcTreeKey key(static_cast<octomap::key_type>(g.first[0] + i + kKeyOffset),
                                 static_cast<octomap::key_type>(g.first[1] + j + kKeyOffset),
                                 static_cast<octomap::key_type>(g.first[2] + k + kKeyOffset));
    tree.setNodeValue(key, occupied, /*lazy_eval=*/true);
  };
  for (int i = 0; i < g.size[0]; ++i) {
    for (int j = 0; j < g.size[1]; ++j) {
      for (int k = 0; k < g.size[2]; ++k) {
        if (!occupancy.occupied(i, j, k)) continue;
        set_occupied(i, j, k);
        ++out.occupied_voxels;
      }
    }
  }
  tree.updateInnerOccupancy();
  tree.prune();
  out.octree_seconds = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  out.field = DistanceField(g, max_distance, nearest_voxels(tree, g, max_distance), arena, faces);
  out.edt_seconds = seconds_since(t0);

  // The faces join the tree only now: the EDT does not need them (the field treats them as exact planes).
  t0 = std::chrono::steady_clock::now();
  tree.enableChangeDetection(false);  // the EDT switched it on; it would record every key set below
  tree.resetChangeDetection();
  for_each_boundary_cell(g, faces.floor, faces.ceiling, faces.walls, [&](int i, int j, int k) {
    if (occupancy.occupied(i, j, k)) return;
    set_occupied(i, j, k);
    ++out.occupied_voxels;
  });

  out.octree_bt = serialize(tree);
  out.octree_seconds += seconds_since(t0);
  return out;
}

}  // namespace peg3d::world
