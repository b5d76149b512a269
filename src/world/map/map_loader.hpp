#pragma once
// Reading a map file: the YAML format of docs/maps.md into a MapSpec, every problem a MapError naming the
// file, the line and the field.

#include <filesystem>

#include "world/map/map_spec.hpp"

namespace peg3d::world {

/// Reads and validates a YAML map (docs/maps.md): every problem throws MapError naming file, line and
/// field. Terrain meshes are imported to check them (missing, empty, malformed, no triangles, non-finite).
MapSpec load_map(const std::filesystem::path& file);

}  // namespace peg3d::world
