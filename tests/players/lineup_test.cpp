#include "players/lineup.hpp"

#include <gtest/gtest.h>

#include "core/random.hpp"

namespace peg3d::players {
namespace {

using namespace peg3d::game;

TEST(Lineup, TheFirstAgentOfARoleKeepsTheRoleSeed) {
  EXPECT_EQ(agent_seed(77, 0), 77u);
  EXPECT_EQ(agent_seed(77, 1), derive_seed(77, {1}));
  EXPECT_NE(agent_seed(77, 1), agent_seed(77, 2));
}

TEST(Lineup, AgentsWithEqualSettingsShareOneModel) {
  GameConfig c = preset("peg3d");
  c.pursuers = {c.pursuer, c.pursuer, c.pursuer};
  c.pursuers[2].facl.actor_rate = 0.01;  // a different learner
  c.pursuers.push_back(c.pursuer);
  c.pursuers[3].policy = "pure-pursuit";
  Lineup l;
  RoleModels models;
  add_configured(l, c, Role::kPursuer, 4, 5, &models);
  EXPECT_EQ(l.size(), 4);
  ASSERT_EQ(models.models.size(), 2u);
  EXPECT_EQ(models.of_agent, (std::vector<int>{0, 0, 1, -1}));
  EXPECT_EQ(&dynamic_cast<FaclPolicy&>(l[0]).model(), &dynamic_cast<FaclPolicy&>(l[1]).model());
  EXPECT_NE(&dynamic_cast<FaclPolicy&>(l[0]).model(), &dynamic_cast<FaclPolicy&>(l[2]).model());
  EXPECT_EQ(models.for_agent(1).get(), models.models[0].get());
  EXPECT_EQ(models.for_agent(3), nullptr);  // the scripted agent has none
}

TEST(Lineup, FrozenAgentsPastTheTrainedOnesPlayTheLastModel) {
  const GameConfig c = preset("peg3d");
  Lineup trained;
  RoleModels models;
  add_configured(trained, c, Role::kEvader, 2, 1, &models);
  Lineup frozen;
  add_frozen(frozen, models, 3);
  EXPECT_EQ(frozen.size(), 3);
  EXPECT_EQ(&dynamic_cast<FaclPolicy&>(frozen[2]).model(), models.models.back().get());
  EXPECT_THROW(frozen[0].begin_episode({}, true), std::logic_error);
  RoleModels none;
  Lineup empty;
  EXPECT_THROW(add_frozen(empty, none, 1), std::logic_error);
}

}  // namespace
}  // namespace peg3d::players
