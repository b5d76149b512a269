// Mesh import through assimp: every supported format, placement transforms, and broken files.

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "world/triangle_mesh.hpp"
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
  expect_mesh_error("truncated.ply", "has no triangles");
  expect_mesh_error("truncated_header.ply", "no end_header");
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
