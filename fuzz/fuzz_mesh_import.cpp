// libFuzzer target: the mesh checks and assimp's import, in process (import_mesh_in_process), so a crash or a
// runaway allocation in either is seen. The first byte picks the format (the file's extension); the rest is
// the file. Every outcome but a mesh or a MeshError is a finding.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input_file.hpp"
#include "world/map/triangle_mesh.hpp"

extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

namespace {
constexpr std::array<const char*, 7> kExtensions{".obj", ".stl", ".ply", ".off", ".gltf", ".glb", ".3ds"};
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string name = std::string("mesh") + kExtensions[data[0] % kExtensions.size()];
  const auto file = peg3d::fuzz::write_input(data + 1, size - 1, name);
  try {
    (void)peg3d::world::import_mesh_in_process(file);
  } catch (const peg3d::world::MeshError&) {
  }
  return 0;
}
