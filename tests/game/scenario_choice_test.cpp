// Which scenarios a run of one team size plays (game/scenario_choice.hpp), and the most agents of a role.
#include "game/scenario_choice.hpp"

#include <gtest/gtest.h>

#include "core/validation.hpp"

namespace peg3d::game {
namespace {

world::Scenario scenario(const std::string& name, int pursuers, int evaders) {
  world::Scenario s;
  s.name = name;
  s.pursuers.resize(std::size_t(pursuers));
  s.evaders.resize(std::size_t(evaders));
  return s;
}

// Two 1 v 1 scenarios around a 3 v 1 and a 1 v 2.
world::MapSpec map() {
  world::MapSpec m;
  m.scenarios = {scenario("a", 1, 1), scenario("team", 3, 1), scenario("b", 1, 1), scenario("pair", 1, 2)};
  return m;
}

std::string refusal(const world::MapSpec& m, const std::vector<std::string>& names) {
  try {
    scenarios_of_one_team_size(m, names, "scenario");
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.parameter(), "scenario");
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return "";
}

TEST(GameScenarioChoice, NamedScenariosAreTakenInTheirOrder) {
  EXPECT_EQ(scenarios_of_one_team_size(map(), {"b", "a"}, "scenario"), (std::vector<int>{2, 0}));
  EXPECT_EQ(scenarios_of_one_team_size(map(), {"team"}, "scenario"), (std::vector<int>{1}));
  EXPECT_EQ(scenarios_of_one_team_size(map(), {"pair"}, "scenario"), (std::vector<int>{3}));
}

TEST(GameScenarioChoice, NoNamesTakeEveryScenarioOfTheFirstOnesTeamSizes) {
  EXPECT_EQ(scenarios_of_one_team_size(map(), {}, "scenario"), (std::vector<int>{0, 2}));
  world::MapSpec m = map();
  std::swap(m.scenarios[0], m.scenarios[1]);  // the 3 v 1 first
  EXPECT_EQ(scenarios_of_one_team_size(m, {}, "scenario"), (std::vector<int>{0}));
}

TEST(GameScenarioChoice, AnUnknownNameOrAnotherTeamSizeIsRefusedNamingTheField) {
  const std::string unknown = refusal(map(), {"a", "nowhere"});
  EXPECT_NE(unknown.find("nowhere"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("a, team, b, pair"), std::string::npos) << unknown;
  const std::string mixed = refusal(map(), {"b", "pair"});
  EXPECT_NE(mixed.find("pair"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("than b"), std::string::npos) << mixed;
  EXPECT_NE(refusal(world::MapSpec{}, {}).find("no scenario"), std::string::npos);
}

TEST(GameScenarioChoice, MostAgentsOfARoleOverEveryScenario) {
  EXPECT_EQ(most_agents(map(), Role::kPursuer), 3);
  EXPECT_EQ(most_agents(map(), Role::kEvader), 2);
  EXPECT_EQ(most_agents(world::MapSpec{}, Role::kEvader), 0);
}

}  // namespace
}  // namespace peg3d::game
