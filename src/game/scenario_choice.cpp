#include "game/scenario_choice.hpp"

#include <algorithm>

#include "core/validation.hpp"

namespace peg3d::game {
namespace {

bool same_teams(const world::Scenario& a, const world::Scenario& b) {
  return a.pursuers.size() == b.pursuers.size() && a.evaders.size() == b.evaders.size();
}

}  // namespace

std::vector<int> scenarios_of_one_team_size(const world::MapSpec& map, const std::vector<std::string>& names,
                                            const std::string& field) {
  const auto& all = map.scenarios;
  if (all.empty()) throw InvalidParameter(field, "(none)", "the map has no scenario");
  std::vector<int> chosen;
  if (names.empty()) {
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (same_teams(all[i], all.front())) chosen.push_back(int(i));
    }
    return chosen;
  }
  for (const std::string& name : names) {
    const auto it = std::find_if(all.begin(), all.end(), [&](const world::Scenario& s) { return s.name == name; });
    if (it == all.end()) {
      std::string known;
      for (const auto& s : all) known += (known.empty() ? "" : ", ") + s.name;
      throw InvalidParameter(field, name, "is not a scenario of the map (" + known + ")");
    }
    const world::Scenario& head = chosen.empty() ? *it : all[std::size_t(chosen.front())];
    if (!same_teams(*it, head)) {
      throw InvalidParameter(field, name, "has other numbers of pursuers and evaders than " + head.name +
                                              " (the games of a run play one team size)");
    }
    chosen.push_back(int(it - all.begin()));
  }
  return chosen;
}

int most_agents(const world::MapSpec& map, Role role) {
  std::size_t most = 0;
  for (const world::Scenario& s : map.scenarios) {
    most = std::max(most, role == Role::kPursuer ? s.pursuers.size() : s.evaders.size());
  }
  return int(most);
}

}  // namespace peg3d::game
