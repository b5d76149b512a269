#pragma once
// Triangle meshes as plain arrays, and their import through assimp (OBJ, STL, PLY, 3DS, OFF, glTF, ...).

#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "geometry/vector.hpp"

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

/// A mesh file that cannot be used; what() says why, naming the file.
class MeshError : public InputError {
 public:
  using InputError::InputError;
};

/// Imports every triangle of a mesh file (all its meshes, node transforms applied) in the file's own units.
/// Throws MeshError if the file is missing, empty, malformed, holds no triangles, or has a non-finite vertex.
TriangleMesh import_mesh(const std::filesystem::path& file);

/// Places a mesh in the world: v' = R * (scale * v) + translation (see TerrainMesh).
void transform_mesh(TriangleMesh& mesh, double scale, const Vec3& rotation_deg, const Vec3& translation);

/// import_mesh followed by transform_mesh with the entry's placement.
TriangleMesh load_terrain_mesh(const TerrainMesh& entry);

}  // namespace peg3d::world
