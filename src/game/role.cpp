#include "game/role.hpp"

#include <algorithm>
#include <string_view>

namespace peg3d::game {

const char* to_string(Role r) { return r == Role::kPursuer ? "pursuer" : "evader"; }

std::string agent_label(Role role, int rank) { return std::string(to_string(role)) + "_" + std::to_string(rank); }

std::string current_agent_label(const std::string& label) {
  for (const Role role : {Role::kPursuer, Role::kEvader}) {
    const std::string_view name = to_string(role);
    if (!label.starts_with(name)) continue;
    const std::string_view rest = std::string_view(label).substr(name.size());
    if (rest.empty()) return agent_label(role, 0);
    if (rest.size() <= 6 && std::all_of(rest.begin(), rest.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      return std::string(name) + "_" + std::string(rest);
    }
  }
  return label;
}

}  // namespace peg3d::game
