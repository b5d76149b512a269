#pragma once
// Builds the OctoMap OcTree from an occupancy bitmap and the distance field from the tree with
// dynamicEDT3D. OctoMap types stay in the .cpp.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "world/field/distance_field.hpp"
#include "world/field/voxel_grid.hpp"

namespace peg3d::world {

struct FieldBuild {
  DistanceField field;
  std::string octree_bt;            ///< the OcTree serialized in OctoMap's binary .bt format
  std::size_t occupied_voxels = 0;  ///< max-depth voxels occupied in the tree
  double octree_seconds = 0.0;      ///< wall time to fill and serialize the tree
  double edt_seconds = 0.0;         ///< wall time of DynamicEDTOctomap (initialization, update, copy-out)
};

/// Peak memory (bytes) the build needs for a grid: DynamicEDT3D's dense cells (24 bytes) and row pointers,
/// the occupancy bitmap and the compact field.
std::size_t estimate_build_bytes(const VoxelGrid& grid);

/// The field is computed by DynamicEDTOctomap over the whole grid from the occupied cells (unknown space is
/// free), capped at max_distance plus a voxel diagonal so answers are right up to max_distance, and copied
/// into the compact DistanceField, which adds the chosen arena faces as exact planes. The tree then also gets
/// the faces' padding layers, so the exported octree shows every obstacle (all as fully occupied leaves,
/// pruned).
/// The octree of a built world (OctoMap .bt contents) with the cells of posed shapes marked occupied too (the
/// movers at some instant), as .bt contents.
std::string octree_with_shapes(const std::string& octree_bt, const VoxelGrid& grid,
                               const std::vector<std::pair<Shape, Pose>>& shapes);

FieldBuild build_distance_field(const Occupancy& occupancy, double max_distance, const Box& arena = {},
                                ArenaFaces faces = {});

}  // namespace peg3d::world
