#include "world/bodies/contact.hpp"

#include <array>
#include <cstddef>

namespace peg3d::world {

const char* to_string(ObstacleKind kind) {
  static constexpr std::array<const char*, 6> kNames{"sphere", "cylinder", "mesh", "boundary", "agent", "mover"};
  const auto k = static_cast<std::size_t>(kind);
  return k < kNames.size() ? kNames[k] : "?";
}

}  // namespace peg3d::world
