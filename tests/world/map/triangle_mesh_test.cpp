// Mesh import through assimp: every supported format, placement transforms, and broken files.

#include <chrono>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "world/map/mesh_file_checks.hpp"
#include "world/map/triangle_mesh.hpp"
#include "world_test_support.hpp"

// assimp 5.2's ASCII STL reader leaks the mesh it was filling when a file ends mid-facet (the truncation test
// below); LeakSanitizer, when the tests run with PEG3D_SANITIZE=address, is told to ignore that library.
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

namespace peg3d::world {
namespace {

class WorldMeshFormat : public ::testing::TestWithParam<std::string> {};

TEST_P(WorldMeshFormat, CubeImportsWithTwelveTriangles) {
  const TriangleMesh m = import_mesh(testing::mesh_path("cube." + GetParam()));
  EXPECT_EQ(m.triangle_count(), 12u);
  const Box b = m.bounds();
  EXPECT_TRUE(b.lo.isApprox(Vec3::Constant(-1), 1e-6)) << b.lo.transpose();
  EXPECT_TRUE(b.hi.isApprox(Vec3::Constant(1), 1e-6)) << b.hi.transpose();
  // A closed cube: the triangles' areas sum to its surface, 6 faces of 4 m^2.
  double area = 0.0;
  for (const auto& f : m.faces) {
    area += 0.5 * (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]).norm();
  }
  EXPECT_NEAR(area, 24.0, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Formats, WorldMeshFormat, ::testing::Values("obj", "stl", "ply", "3ds", "off", "gltf"));

TEST(WorldMeshImport, PlacementScalesRotatesThenTranslates) {
  TriangleMesh m = import_mesh(testing::mesh_path("wall.obj"));  // x = 0, |y| <= 5, 0 <= z <= 10
  transform_mesh(m, 0.5, Vec3(0, 0, 90), Vec3(1, 2, 3));
  // Scaled: |y| <= 2.5, z <= 5; turned 90 deg about z: the wall now spans x in [-2.5, 2.5] at y = 0.
  const Box b = m.bounds();
  EXPECT_TRUE(b.lo.isApprox(Vec3(-1.5, 2, 3), 1e-12)) << b.lo.transpose();
  EXPECT_TRUE(b.hi.isApprox(Vec3(3.5, 2, 8), 1e-12)) << b.hi.transpose();
}

TEST(WorldMeshImport, RotationsApplyAboutXThenYThenZ) {
  TriangleMesh m;
  m.vertices = {Vec3(1, 0, 0)};
  transform_mesh(m, 1.0, Vec3(90, 90, 0), Vec3::Zero());
  // x first leaves (1, 0, 0) alone; then 90 deg about y takes it to (0, 0, -1).
  EXPECT_TRUE(m.vertices[0].isApprox(Vec3(0, 0, -1), 1e-12)) << m.vertices[0].transpose();
}

TEST(WorldMeshImport, ValleyAssetHasAFewThousandTriangles) {
  const TriangleMesh m = import_mesh(testing::source_dir() / "assets" / "valley.obj");
  EXPECT_EQ(m.triangle_count(), 3200u);
  EXPECT_EQ(m.vertices.size(), 41u * 41u);
}

void expect_mesh_error(const std::string& name, const std::string& fragment) {
  try {
    import_mesh(testing::mesh_path(name));
    ADD_FAILURE() << name << " imported";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
  }
}

TEST(WorldMeshImport, BrokenFilesAreRejectedWithTheReason) {
  expect_mesh_error("no_such_file.obj", "not found");
  expect_mesh_error("empty.obj", "is empty");
  expect_mesh_error("garbage.obj", "cannot be read");
  expect_mesh_error("lines_only.obj", "has no triangles");
  expect_mesh_error("nan_vertex.obj", "non-finite vertex");
  expect_mesh_error("truncated.ply", "declares 8 PLY elements");
  expect_mesh_error("truncated_header.ply", "no end_header");
}

// tests/data/meshes/hostile/ (tools/make_test_meshes.py): every accepted format empty, truncated, garbage, with
// absurd declared counts, non-finite or huge coordinates, degenerate triangles and out-of-range indices, and
// the glTF attacks on assimp. expect.txt gives each file's message fragment; each is refused within the
// import's time bound.
std::map<std::string, std::string> hostile_expectations() {
  std::map<std::string, std::string> out;
  std::ifstream in(testing::mesh_path("hostile") / "expect.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t space = line.find(' ');
    out[line.substr(0, space)] = line.substr(space + 1);
  }
  return out;
}

TEST(WorldMeshImport, EveryHostileFileIsRefusedWithItsReasonInTime) {
  const auto expectations = hostile_expectations();
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::mesh_path("hostile"))) {
    const std::string name = entry.path().filename().string();
    if (name == "expect.txt") continue;
    ++files;
    SCOPED_TRACE(name);
    const auto want = expectations.find(name);
    const auto start = std::chrono::steady_clock::now();
    try {
      const TriangleMesh m = import_mesh(entry.path());
      ADD_FAILURE() << "imported " << m.triangle_count() << " triangles";
    } catch (const MeshError& e) {
      const std::string what = e.what();
      if (want == expectations.end()) {
        ADD_FAILURE() << "expect.txt has no line for it; it says: " << what;
        continue;
      }
      EXPECT_NE(what.find(entry.path().string()), std::string::npos) << what;
      EXPECT_NE(what.find(want->second), std::string::npos) << what;
      EXPECT_LT(what.size(), entry.path().string().size() + 300) << what;
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  }
  EXPECT_EQ(files, expectations.size()) << "expect.txt names a file that is not there";
}

TEST(WorldMeshImport, AGltfBufferBesideTheFileIsReadAndOneOutsideIsNot) {
  testing::ScratchDir dir;
  std::filesystem::create_directories(dir / "mesh");
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (const char* name : {"mesh/tri.bin", "tri.bin"}) {
    std::ofstream(dir / name, std::ios::binary).write(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  const auto gltf = [&](const std::string& uri) {
    const auto file = dir / "mesh" / "tri.gltf";
    std::ofstream(file) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 4}]}],
      "buffers": [{"byteLength": 36, "uri": ")" << uri << R"("}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}]})";
    return file;
  };
  EXPECT_EQ(import_mesh(gltf("tri.bin")).triangle_count(), 1u);
  EXPECT_THROW(import_mesh(gltf("../tri.bin")), MeshError);
  EXPECT_TRUE(is_safe_mesh_reference(dir / "mesh" / "tri.gltf", dir / "mesh" / "tri.bin"));
  EXPECT_FALSE(is_safe_mesh_reference(dir / "mesh" / "tri.gltf", dir / "mesh" / ".." / "tri.bin"));
  EXPECT_FALSE(is_safe_mesh_reference(dir / "mesh" / "tri.gltf", "/dev/zero"));
  std::filesystem::create_symlink(dir / "tri.bin", dir / "mesh" / "link.bin");
  EXPECT_FALSE(is_safe_mesh_reference(dir / "mesh" / "tri.gltf", dir / "mesh" / "link.bin")) << "a link out of the folder";
}

TEST(WorldMeshImport, InProcessImportGivesTheSameMesh) {
  for (const std::string ext : {"obj", "stl", "ply", "3ds", "off", "gltf"}) {
    const TriangleMesh a = import_mesh(testing::mesh_path("cube." + ext));
    const TriangleMesh b = import_mesh_in_process(testing::mesh_path("cube." + ext));
    EXPECT_EQ(a.vertices, b.vertices) << ext;
    EXPECT_EQ(a.faces, b.faces) << ext;
  }
}

TEST(WorldMeshImport, TruncatedFilesNeverCrash) {
  // Every prefix of every format either imports or throws MeshError: assimp's aborting assertions and its
  // PLY header loop must not be reachable from a cut-off file.
  testing::ScratchDir dir;
  for (const std::string ext : {"obj", "stl", "ply", "3ds", "off", "gltf"}) {
    std::ifstream in(testing::mesh_path("cube." + ext), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t step = std::max<std::size_t>(1, bytes.size() / 40);
    for (std::size_t n = 1; n < bytes.size(); n += step) {
      const auto file = dir / ("cut." + ext);
      std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(n));
      try {
        const TriangleMesh m = import_mesh(file);
        EXPECT_LE(m.triangle_count(), 12u);
      } catch (const MeshError&) {
      }
    }
  }
}

}  // namespace
}  // namespace peg3d::world

namespace peg3d::world {
namespace {

// A million-triangle text OBJ (35 MB) needs about 1.5 GiB of address space to import: the bounds grow with
// the file, from 8 s and 768 MiB for small files, up to 8 GiB.
TEST(WorldMeshImportLimits, GrowWithTheFileUpToTheCap) {
  const MeshImportLimits l;
  EXPECT_EQ(l.memory_for(0), std::size_t{768} << 20);
  EXPECT_EQ(l.memory_for(1'000'000), std::size_t{768} << 20);
  EXPECT_EQ(l.memory_for(35'000'000), std::size_t{64} * 35'000'000);
  EXPECT_EQ(l.memory_for(std::uintmax_t{1} << 40), std::size_t{8} << 30);
  EXPECT_DOUBLE_EQ(l.seconds_for(0), 8.0);
  EXPECT_DOUBLE_EQ(l.seconds_for(std::uintmax_t{10} << 20), 13.0);
}

}  // namespace
}  // namespace peg3d::world
