// A FACL best response (experiment/facl_response.hpp): the learners of one role against a fixed opponent, a classic
// player, a frozen FACL file or a mixture of them.
#include "experiment/facl_response.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "core/hash.hpp"
#include "core/validation.hpp"
#include "game/game_config.hpp"
#include "players/registry.hpp"
#include "support/facl_tables_hash.hpp"
#include "test_arena.hpp"

namespace peg3d::experiment {
namespace {

using game::Role;

// A room with a pillar between the two starts: the pursuer does not see the evader at first.
std::shared_ptr<const world::Arena> room() {
  static const auto a = [] {
    world::MapSpec m = world::testing::empty_spec({30, 30, 10}, 0.25, 5.0);
    m.name = "pillar";
    m.cylinders.push_back({{15, 15, 0}, 3.0, 10.0});
    m.scenarios = {testing::scenario("behind", {5, 15, 5}, {25, 15, 5}), testing::scenario("open", {5, 5, 5}, {25, 5, 5})};
    return world::Arena::build(m);
  }();
  return a;
}

// The peg3d preset in 10 s games, FACL pursuers with limited sight and the sight inputs.
game::GameConfig config() {
  game::GameConfig c = game::preset("peg3d");
  c.time_limit = 10.0;
  game::AgentConfig p = c.agent(Role::kPursuer);
  p.policy = std::string(players::kFacl);
  p.sensors.sight.enabled = true;
  p.sensors.sight.fov = 120.0;
  p.observation.sight_inputs = true;
  c.set_agent(Role::kPursuer, 0, p);
  game::AgentConfig e = c.agent(Role::kEvader);
  e.policy = "flee";
  c.set_agent(Role::kEvader, 0, e);
  return c;
}

std::shared_ptr<const players::SavedPolicy> classic(const char* name) {
  auto s = std::make_shared<players::SavedPolicy>();
  s->members.push_back({name, nullptr, 1.0});
  return s;
}

using testing::tables_hash;

TEST(FaclResponse, IsAPureFunctionOfItsSeed) {
  const game::Sim sim(room(), config());
  const auto flee = classic("flee");
  FaclResponseSettings s;
  s.episodes = 6;
  s.seed = 4;
  const std::uint64_t a = tables_hash(train_facl_response(sim, Role::kPursuer, *flee, s));
  EXPECT_EQ(tables_hash(train_facl_response(sim, Role::kPursuer, *flee, s)), a);
  s.seed = 5;
  EXPECT_NE(tables_hash(train_facl_response(sim, Role::kPursuer, *flee, s)), a);
}

TEST(FaclResponse, AClassicOpponentPlaysFreeOfTheMotionSpace) {
  // FACL evaders against pn, a classic player, alone and drawn from a mixture: peg3d's pursuers keep the motion space,
  // which a classic player plays without (game::begin_playing), so the evaders learn what they learn with it off.
  // A learning evader's tables differ when the pursuer is held (the same pn, not a classic player), so they tell.
  game::GameConfig c = config();
  game::AgentConfig e = game::agent_preset("peg3d", Role::kEvader);
  e.policy = std::string(players::kFacl);
  c.evaders = {e};
  c.pursuers.clear();
  ASSERT_TRUE(c.pursuer.motion_space);
  game::GameConfig off = c;
  off.pursuer.motion_space = false;
  const game::Sim held(room(), c), free_sim(room(), off);
  FaclResponseSettings s;
  s.episodes = 6;
  s.seed = 4;
  auto mixture = std::make_shared<players::SavedPolicy>();
  mixture->members = {{"pn", nullptr, 1.0}, {"pure-pursuit", nullptr, 0.0}};
  for (const auto& pn : {classic("pn"), std::shared_ptr<const players::SavedPolicy>(mixture)}) {
    EXPECT_EQ(tables_hash(train_facl_response(held, Role::kEvader, *pn, s)),
              tables_hash(train_facl_response(free_sim, Role::kEvader, *pn, s)));
  }
}

TEST(FaclResponse, LearnsInSightAndOutOfSightInRulesOfTheirOwn) {
  // Behind the pillar the pursuer starts without sight of the evader, in the open with it: its tables learn where it
  // has lost the evader (visible 0) as well as where it sees it (visible 1), each in rules of its own.
  const game::Sim sim(room(), config());
  FaclResponseSettings s;
  s.episodes = 4;
  s.scenarios = {"behind", "open"};
  const players::RoleModels models = train_facl_response(sim, Role::kPursuer, *classic("flee"), s);
  ASSERT_EQ(models.models.size(), 1u);
  const players::FaclModel& m = *models.models.front();
  const players::FaclModel fresh(m.config(), Role::kPursuer);
  int changed[2] = {0, 0};
  for (int c = 0; c < m.channels(); ++c) {
    const fuzzy::RuleBase& rules = m.tables(c).rules();
    const int visible = rules.inputs() - 2;  // the sight's inputs come last: visible, then age
    ASSERT_EQ(rules.input(visible).sets(), 2);
    // A rule's visibility set is its digit of input `visible` (input 0 is the most significant).
    int stride = 1;
    for (int i = visible + 1; i < rules.inputs(); ++i) stride *= rules.input(i).sets();
    const auto critic = m.tables(c).critic_table(), initial = fresh.tables(c).critic_table();
    for (int l = 0; l < rules.rules(); ++l) changed[(l / stride) % 2] += critic[std::size_t(l)] != initial[std::size_t(l)];
  }
  EXPECT_GT(changed[0], 0);
  EXPECT_GT(changed[1], 0);
}

TEST(FaclResponse, AFrozenFaclOpponentPlaysWithoutLearning) {
  // A FACL evader file, frozen: training against it must not ask it to learn, and leaves its tables as they were.
  game::GameConfig c = config();
  game::AgentConfig e = c.agent(Role::kEvader);
  e.policy = std::string(players::kFacl);
  e.observation.sight_inputs = true;
  auto saved = std::make_shared<players::SavedPolicy>();
  auto model = std::make_shared<players::FaclModel>(e, Role::kEvader);
  saved->facl = model;
  const std::uint64_t before = [&] {
    Fnv1a h;
    h.add_span(model->tables(0).critic_table());
    return h.value();
  }();
  c = with_opponent_config(c, Role::kEvader, 1, *saved);
  EXPECT_EQ(c.agent(Role::kEvader).policy, players::kFacl);
  const game::Sim sim(room(), c);
  FaclResponseSettings s;
  s.episodes = 3;
  EXPECT_NO_THROW(train_facl_response(sim, Role::kPursuer, *saved, s));
  Fnv1a after;
  after.add_span(model->tables(0).critic_table());
  EXPECT_EQ(after.value(), before);
}

TEST(FaclResponse, RefusesWhatItCannotTrain) {
  const auto flee = classic("flee");
  FaclResponseSettings s;
  s.episodes = 1;
  game::GameConfig c = config();
  const game::Sim classic_evaders(room(), c);
  // The evaders play flee, not facl.
  try {
    train_facl_response(classic_evaders, Role::kEvader, *classic("pn"), s);
    ADD_FAILURE() << "an evader that does not play facl was trained";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("evader.policy"), std::string::npos) << e.what();
  }
  s.scenarios = {"behind", "nowhere"};
  try {
    train_facl_response(classic_evaders, Role::kPursuer, *flee, s);
    ADD_FAILURE() << "an unknown scenario was played";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.parameter(), "scenarios");
    EXPECT_NE(std::string(e.what()).find("nowhere"), std::string::npos) << e.what();
  }
  s.scenarios.clear();
  s.episodes = 0;
  EXPECT_THROW(train_facl_response(classic_evaders, Role::kPursuer, *flee, s), InvalidParameter);
}

}  // namespace
}  // namespace peg3d::experiment
