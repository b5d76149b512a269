// libFuzzer target: players::load_policy (a saved FACL policy: JSON header, configuration, tables) on
// arbitrary bytes, for the pursuer's role. Every outcome but a policy or an InputError is a finding.

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input_file.hpp"
#include "players/policy_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = peg3d::fuzz::write_input(data, size, "policy.json");
  try {
    (void)peg3d::players::load_policy(file, peg3d::game::Role::kPursuer);
  } catch (const peg3d::InputError&) {
  }
  return 0;
}
