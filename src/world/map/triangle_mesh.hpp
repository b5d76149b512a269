#pragma once
// Triangle meshes as plain arrays, and their bounded import through assimp (OBJ, STL, PLY, OFF, glTF 2, 3DS).

#include <algorithm>
#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vector.hpp"
#include "world/map/mesh_file_checks.hpp"

namespace peg3d::world {

struct TerrainMesh;

/// An indexed triangle soup in world coordinates (m). The layout (contiguous Vec3 and int[3]) is what Bullet's
/// btTriangleIndexVertexArray reads in place, so the arrays are shared with the collision world, not copied.
struct TriangleMesh {
  std::vector<Vec3> vertices;                ///< m
  std::vector<std::array<int, 3>> faces;     ///< indices into vertices, counter-clockwise seen from outside

  std::size_t triangle_count() const { return faces.size(); }
  /// Axis-aligned bounds of the vertices (lo > hi when empty).
  Box bounds() const;
};

/// How long and how much memory one mesh import may take before it is given up (see import_mesh). Both grow
/// with the file: a text OBJ of a million triangles (35 MB) takes about 2 s, 0.6 GB resident and between 1
/// and 1.5 GiB of address space to import, so a fixed bound would refuse honest terrain while a small file
/// that asks for gigabytes is still stopped early.
struct MeshImportLimits {
  double seconds = 8.0;                                   ///< s of processor time for any file, > 0 (see ChildLimits)
  double seconds_per_mib = 0.5;                           ///< s more per MiB of file, >= 0
  std::size_t memory_bytes = std::size_t{768} << 20;     ///< bytes the import may add to the process, > 0
  std::size_t memory_per_file_byte = 64;                  ///< or this many per byte of file, when more
  std::size_t max_memory_bytes = std::size_t{8} << 30;   ///< and never more than this

  /// The bounds for a file of `file_bytes`.
  double seconds_for(std::uintmax_t file_bytes) const { return seconds + seconds_per_mib * double(file_bytes) / (1 << 20); }
  std::size_t memory_for(std::uintmax_t file_bytes) const {
    const double scaled = double(memory_per_file_byte) * double(file_bytes);
    return std::min(max_memory_bytes, std::max(memory_bytes, scaled >= double(max_memory_bytes) ? max_memory_bytes
                                                                                                  : std::size_t(scaled)));
  }
};

/// Imports every triangle of a mesh file (all its meshes, node transforms applied) in the file's own units.
/// Accepts the formats of kAcceptedMeshFormats (world/map/mesh_file_checks.hpp) only. What the file declares is
/// checked first (check_mesh_declarations); the import itself runs in a child process bounded by `limits`,
/// so a file that makes assimp hang, exhaust memory or crash is a MeshError like any other broken file.
/// Throws MeshError if the file is missing, empty, malformed, holds no triangles, or has a non-finite vertex.
TriangleMesh import_mesh(const std::filesystem::path& file, const MeshImportLimits& limits = {});

/// import_mesh without the child process and its bounds: the same checks, then assimp in this process. For
/// the fuzzer (which must see the importer's crashes) and callers that bound their process themselves.
TriangleMesh import_mesh_in_process(const std::filesystem::path& file);

/// Places a mesh in the world: v' = R * (scale * v) + translation (see TerrainMesh).
void transform_mesh(TriangleMesh& mesh, double scale, const Vec3& rotation_deg, const Vec3& translation);

/// import_mesh followed by transform_mesh with the entry's placement.
TriangleMesh load_terrain_mesh(const TerrainMesh& entry);

}  // namespace peg3d::world
