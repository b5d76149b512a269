#include "world/triangle_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <system_error>

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "world/map_spec.hpp"

namespace peg3d::world {

Box TriangleMesh::bounds() const {
  const double inf = std::numeric_limits<double>::infinity();
  Box b{Vec3::Constant(inf), Vec3::Constant(-inf)};
  for (const Vec3& v : vertices) {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  return b;
}

namespace {

/// assimp 5.2's PLY reader loops forever on a header cut short before "end_header": refuse those up front.
void check_ply_header(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".ply") return;
  std::ifstream in(file, std::ios::binary);
  std::string head(1 << 20, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.find("end_header") == std::string::npos) {
    throw MeshError(fmt::format("mesh file '{}' is malformed: its PLY header has no end_header", file.string()));
  }
}

}  // namespace

TriangleMesh import_mesh(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw MeshError(fmt::format("mesh file '{}' not found", name));
  if (!std::filesystem::is_regular_file(file, ec)) throw MeshError(fmt::format("mesh file '{}' is not a file", name));
  if (std::filesystem::file_size(file, ec) == 0) throw MeshError(fmt::format("mesh file '{}' is empty", name));

  check_ply_header(file);

  Assimp::Importer importer;
  // Read with validation only, check the raw data, then post-process: Debian builds assimp with its internal
  // assertions on, and a post-processing step that meets inconsistent data (e.g. a truncated PLY whose mesh
  // claims polygons but holds no faces) aborts the process instead of failing.
  const aiScene* scene = importer.ReadFile(name, aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    throw MeshError(fmt::format("mesh file '{}' cannot be read: {}", name, importer.GetErrorString()));
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw MeshError(fmt::format("mesh file '{}' is incomplete (malformed or truncated)", name));
  }
  std::size_t surfaces = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    aiMesh* mesh = scene->mMeshes[m];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw MeshError(fmt::format("mesh file '{}' has a non-finite vertex ({}, {}, {})", name, p.x, p.y, p.z));
      }
    }
    // Recompute the primitive types from the faces, so the post-processing sees consistent data.
    unsigned types = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned n = mesh->mFaces[f].mNumIndices;
      types |= n == 1 ? aiPrimitiveType_POINT : n == 2 ? aiPrimitiveType_LINE : n == 3 ? aiPrimitiveType_TRIANGLE
                                                                                     : aiPrimitiveType_POLYGON;
      if (n >= 3) ++surfaces;
    }
    mesh->mPrimitiveTypes = types;
  }
  if (surfaces == 0) throw MeshError(fmt::format("mesh file '{}' has no triangles", name));
  // Drop points and lines after triangulation so only surfaces remain; bake node transforms so multi-node
  // files (glTF, 3DS) come out where their author placed them.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                                       aiProcess_PreTransformVertices);
  if (scene == nullptr) {
    throw MeshError(fmt::format("mesh file '{}' cannot be read: {}", name, importer.GetErrorString()));
  }

  TriangleMesh out;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Vec3 q(p.x, p.y, p.z);
      if (!q.allFinite()) {
        throw MeshError(fmt::format("mesh file '{}' has a non-finite vertex ({}, {}, {})", name, q.x(), q.y(), q.z()));
      }
      out.vertices.push_back(q);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      const std::array<int, 3> t{base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                                 base + static_cast<int>(face.mIndices[2])};
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // collapsed by vertex joining
      out.faces.push_back(t);
    }
  }
  if (out.faces.empty()) throw MeshError(fmt::format("mesh file '{}' has no triangles", name));
  return out;
}

void transform_mesh(TriangleMesh& mesh, double scale, const Vec3& rotation_deg, const Vec3& translation) {
  const Vec3 r = rotation_deg * (kPi / 180.0);
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
                                    Eigen::AngleAxisd(r.x(), Vec3::UnitX()))
                                       .toRotationMatrix();
  for (Vec3& v : mesh.vertices) v = rotation * (scale * v) + translation;
}

TriangleMesh load_terrain_mesh(const TerrainMesh& entry) {
  TriangleMesh mesh = import_mesh(entry.file);
  transform_mesh(mesh, entry.scale, entry.rotation_deg, entry.translation);
  return mesh;
}

}  // namespace peg3d::world
