#include "world/map/triangle_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <new>
#include <fstream>
#include <limits>
#include <system_error>

#include <Eigen/Geometry>
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "core/bounded_child.hpp"
#include "world/map/map_spec.hpp"

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

// Lets assimp open the mesh file and the files it names (glTF buffers, OBJ material libraries) only when they
// are regular files inside the mesh's folder: a mesh from a stranger must not read /dev/zero or ../../secret.
class FolderIOSystem : public Assimp::DefaultIOSystem {
 public:
  explicit FolderIOSystem(std::filesystem::path mesh) : mesh_(std::move(mesh)) {}
  bool Exists(const char* file) const override { return allowed(file) && Assimp::DefaultIOSystem::Exists(file); }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!allowed(file) || mode == nullptr || std::strchr(mode, 'w') != nullptr || std::strchr(mode, 'a') != nullptr) {
      return nullptr;
    }
    return Assimp::DefaultIOSystem::Open(file, mode);
  }

 private:
  bool allowed(const char* file) const { return file != nullptr && is_safe_mesh_reference(mesh_, file); }
  std::filesystem::path mesh_;
};

// A mesh as bytes through the child's pipe: vertex and face counts, then the raw arrays.
std::string serialize(const TriangleMesh& m) {
  const std::uint64_t counts[2] = {m.vertices.size(), m.faces.size()};
  std::string out(reinterpret_cast<const char*>(counts), sizeof counts);
  out.append(reinterpret_cast<const char*>(m.vertices.data()), m.vertices.size() * sizeof(Vec3));
  out.append(reinterpret_cast<const char*>(m.faces.data()), m.faces.size() * sizeof(std::array<int, 3>));
  return out;
}

TriangleMesh deserialize(const std::string& bytes, const std::string& name) {
  std::uint64_t counts[2] = {0, 0};
  if (bytes.size() >= sizeof counts) std::memcpy(counts, bytes.data(), sizeof counts);
  if (bytes.size() < sizeof counts || counts[0] > bytes.size() || counts[1] > bytes.size() ||
      bytes.size() != sizeof counts + counts[0] * sizeof(Vec3) + counts[1] * sizeof(std::array<int, 3>)) {
    throw MeshError(fmt::format("mesh file '{}' could not be imported: the importer's result was cut short", name));
  }
  TriangleMesh m;
  m.vertices.resize(counts[0]);
  m.faces.resize(counts[1]);
  const std::size_t vertex_bytes = counts[0] * sizeof(Vec3);
  std::memcpy(static_cast<void*>(m.vertices.data()), bytes.data() + sizeof counts, vertex_bytes);
  std::memcpy(static_cast<void*>(m.faces.data()), bytes.data() + sizeof counts + vertex_bytes,
              counts[1] * sizeof(std::array<int, 3>));
  return m;
}

void check_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw MeshError(fmt::format("mesh file '{}' not found", name));
  if (!std::filesystem::is_regular_file(file, ec)) throw MeshError(fmt::format("mesh file '{}' is not a file", name));
  if (std::filesystem::file_size(file, ec) == 0) throw MeshError(fmt::format("mesh file '{}' is empty", name));
  check_mesh_declarations(file);
}

TriangleMesh import_checked(const std::filesystem::path& file) {
  const std::string name = file.string();
  Assimp::Importer importer;
  importer.SetIOHandler(new FolderIOSystem(file));  // the importer owns it
  // Read with validation only, check the raw data, then post-process: Debian builds assimp with its internal
  // assertions on, and a post-processing step that meets inconsistent data (e.g. a truncated PLY whose mesh
  // claims polygons but holds no faces) aborts the process instead of failing.
  const aiScene* scene = importer.ReadFile(name, aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    const std::string why = importer.GetErrorString();
    // assimp reports a failed allocation (under the child's memory cap) as its error string.
    if (why == "std::bad_alloc") throw std::bad_alloc();  // the whole message, never text quoted from the file
    throw MeshError(fmt::format("mesh file '{}' cannot be read: {}", name, why));
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

}  // namespace

TriangleMesh import_mesh_in_process(const std::filesystem::path& file) {
  check_file(file);
  try {
    return import_checked(file);
  } catch (const std::bad_alloc&) {
    throw MeshError(fmt::format("mesh file '{}' needed more memory than there is to import: it is malformed or too large",
                                file.string()));
  }
}

namespace {
// Code built with AddressSanitizer or ThreadSanitizer runs several times slower, and its child's copy-on-write
// faults on the shadow memory count as processor time too: the project's own valley.obj once passed the 8 s
// meant for hostile files in a sanitized test. The bound scales with the build, so it trips on hostile input
// only (the hostile corpus is checked in such builds with its time limits doubled, and never reaches it).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr double kBuildSlowdown = 4.0;
#else
constexpr double kBuildSlowdown = 1.0;
#endif
}  // namespace

TriangleMesh import_mesh(const std::filesystem::path& file, const MeshImportLimits& limits) {
  check_file(file);
  const std::string name = file.string();
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(file, ec);
  const double seconds = kBuildSlowdown * limits.seconds_for(ec ? 0 : bytes);
  const std::size_t memory = limits.memory_for(ec ? 0 : bytes);
  const ChildResult r = run_bounded(
      [&] {
        try {
          return serialize(import_checked(file));
        } catch (const MeshError&) {
          throw;
        } catch (const std::bad_alloc&) {
          throw;
        } catch (const std::exception& e) {
          throw MeshError(fmt::format("mesh file '{}' cannot be read: {}", name, e.what()));
        }
      },
      {seconds, memory});
  switch (r.status) {
    case ChildResult::Status::kOk:
      return deserialize(r.output, name);
    case ChildResult::Status::kFailed:
      throw MeshError(r.output);
    case ChildResult::Status::kTimedOut:
      throw MeshError(fmt::format("mesh file '{}' took more than {:.1f} s of processor time to import and was given up: it is malformed or too "
                                  "large",
                                  name, seconds));
    case ChildResult::Status::kBlocked:
      throw MeshError(fmt::format("mesh file '{}' was given up after {:.1f} s by the clock, in which its import used "
                                  "less than its {:.1f} s of processor time: the import was blocked, not the file "
                                  "too large (a lock another thread of this process held when the import started)",
                                  name, seconds * ChildLimits::kWallTimeFactor, seconds));
    case ChildResult::Status::kOutOfMemory:
      throw MeshError(fmt::format("mesh file '{}' needed more memory than the {} MiB an import may use and was given up: "
                                  "it is malformed or too large",
                                  name, memory >> 20));
    case ChildResult::Status::kCrashed:
      break;
  }
  throw MeshError(fmt::format("mesh file '{}' crashed the importer ({}): it is malformed", name, r.output));
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
