#pragma once
// Builds the OctoMap OcTree from an occupancy bitmap and the distance field from the tree with
// dynamicEDT3D. OctoMap types stay in the .cpp.

#include <cstddef>
#include <string>

#include "world/distance_field.hpp"
#include "world/voxel_grid.hpp"

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

/// The tree holds exactly the occupied cells (as fully occupied leaves, pruned); the field is computed by
/// DynamicEDTOctomap over the whole grid with unknown space as free, capped at max_distance plus two voxel
/// diagonals so answers are exact up to max_distance, then copied into the compact DistanceField.
FieldBuild build_distance_field(const Occupancy& occupancy, double max_distance);

}  // namespace peg3d::world
