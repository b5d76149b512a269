// libFuzzer target: world::load_map on arbitrary bytes. Every outcome but a map or an InputError is a finding.

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input_file.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"

extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = peg3d::fuzz::write_input(data, size, "map.yaml");
  try {
    (void)peg3d::world::load_map(file);
  } catch (const peg3d::InputError&) {
  }
  return 0;
}
