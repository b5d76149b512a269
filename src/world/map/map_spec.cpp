#include "world/map/map_spec.hpp"

namespace peg3d::world {

const Scenario* MapSpec::find_scenario(const std::string& wanted) const {
  for (const Scenario& s : scenarios) {
    if (s.name == wanted) return &s;
  }
  return nullptr;
}

}  // namespace peg3d::world
