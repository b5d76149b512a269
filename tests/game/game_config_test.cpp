#include "game/game_config.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/config_json.hpp"
#include "core/config_overrides.hpp"
#include "core/validation.hpp"

namespace peg3d::game {
namespace {

// A value of the same JSON type as `old` that differs from it and is valid for the field (numbers grow a
// little, flags flip, enumerations take another of their names).
nlohmann::json changed(const std::string& key, const nlohmann::json& old) {
  if (old.is_boolean()) return !old.get<bool>();
  if (old.is_number_integer() || old.is_number_unsigned()) return old.get<int>() + 1;
  if (old.is_number()) {
    const double v = old.get<double>();
    // Stay inside every range: (0, 1] rates and [0, 1) discounts shrink, angles stay below pi/2.
    return v > 0.0 ? v * 0.75 : v + 0.125;
  }
  const std::string text = old.get<std::string>();
  for (const auto& candidates : std::vector<std::vector<std::string>>{
           {"facl", "random"}, {"per-step", "per-second"}, {"azimuth", "azimuth-elevation"},
           {"toward-pursuer", "away-from-pursuer"}, {"joint", "per-angle"}, {"potential-field", "distance-only"},
           {"negate", "mirror"}, {"terminate", "penalize"}, {"chase", "facing"}, {"nearest", "assigned"},
           {"none", "all"}, {"individual", "team"}, {"exact", "octree"}, {"shared", "push"}, {"co-learning", "opponent-pool"},
           {"heading-change", "target-line-offset"}, {"world", "own-map"}, {"last-seen", "dead-reckoning"}}) {
    for (std::size_t i = 0; i < candidates.size(); ++i)
      if (candidates[i] == text) return candidates[1 - i];
  }
  ADD_FAILURE() << key << ": no other value known for \"" << text << "\"";
  return old;
}

TEST(GameConfig, EveryFieldTravelsThroughJsonBothWays) {
  // For every leaf of the JSON image: change it, read the image back, and check the struct changed and
  // writes the new value. A field that one direction forgets fails here.
  const GameConfig base = preset("peg3d");
  const nlohmann::json image = config::to_json(base);
  int leaves = 0;
  for (const std::string& line : config::flatten(image)) {
    const std::string key = line.substr(0, line.find('='));
    if (key == "pursuers" || key == "evaders") continue;  // empty lists: their elements are agents, checked below
    nlohmann::json j = image;
    const nlohmann::json::json_pointer ptr("/" + [&] {
      std::string k = key;
      for (char& c : k) c = c == '.' ? '/' : c;
      return k;
    }());
    j[ptr] = changed(key, j[ptr]);
    GameConfig back = base;
    config::from_json(j, back);
    EXPECT_NE(back, base) << key << " did not reach the struct";
    EXPECT_EQ(config::to_json(back)[ptr], j[ptr]) << key << " is not written back";
    ++leaves;
  }
  // 75 per agent (11 of its lidar, 10 of its camera, 9 of its map, 6 of its sight, 2 sight inputs), 7 game and 4
  // team fields (training is the experiments': experiment::TrialConfig)
  EXPECT_EQ(leaves, 2 * 75 + 11);
}

TEST(GameConfig, TablesListEveryMemberOfEveryStruct) {
  // The field tables and the structs have the same number of members: a member added to a struct and not to
  // its table (so neither read nor written, nor validated) is caught here.
  EXPECT_EQ(config::table_field_count<GameConfig>(), static_cast<int>(config::member_count<GameConfig>()));
  EXPECT_EQ(config::table_field_count<AgentConfig>(), static_cast<int>(config::member_count<AgentConfig>()));
  EXPECT_EQ(config::table_field_count<TeamConfig>(), static_cast<int>(config::member_count<TeamConfig>()));
  EXPECT_EQ(config::table_field_count<sense::SightConfig>(), static_cast<int>(config::member_count<sense::SightConfig>()));
  EXPECT_EQ(config::table_field_count<ObservationConfig>(), static_cast<int>(config::member_count<ObservationConfig>()));
  EXPECT_EQ(config::table_field_count<RewardConfig>(), static_cast<int>(config::member_count<RewardConfig>()));
  EXPECT_EQ(config::table_field_count<sense::LidarConfig>(), static_cast<int>(config::member_count<sense::LidarConfig>()));
  EXPECT_EQ(config::table_field_count<sense::DepthCameraConfig>(),
            static_cast<int>(config::member_count<sense::DepthCameraConfig>()));
  EXPECT_EQ(config::table_field_count<sense::SensorSettings>(),
            static_cast<int>(config::member_count<sense::SensorSettings>()));
  EXPECT_EQ(config::table_field_count<sense::ScanMapConfig>(), static_cast<int>(config::member_count<sense::ScanMapConfig>()));
  EXPECT_EQ(config::table_field_count<ObstacleGuard>(), static_cast<int>(config::member_count<ObstacleGuard>()));
  EXPECT_EQ(config::table_field_count<SteeringConfig>(), static_cast<int>(config::member_count<SteeringConfig>()));
  EXPECT_EQ(config::table_field_count<fuzzy::FaclConfig>(), static_cast<int>(config::member_count<fuzzy::FaclConfig>()));
}

TEST(GameConfig, ListingShowsEveryFieldWithItsValue) {
  const GameConfig c = preset("paper");
  const auto fields = config::list_fields(c);
  std::vector<std::string> keys;
  for (const auto& f : fields) keys.push_back(f.key);
  for (const std::string& line : config::flatten(config::to_json(c))) {
    const std::string key = line.substr(0, line.find('='));
    EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key;
  }
  const auto rate = std::find_if(fields.begin(), fields.end(), [](const auto& f) { return f.key == "pursuer.facl.actor_rate"; });
  ASSERT_NE(rate, fields.end());
  EXPECT_EQ(rate->value, "0.001");
  EXPECT_EQ(rate->valid, "in (0, 1]");
}

TEST(GameConfig, UnknownKeysAndWrongTypesAreErrorsNamingTheField) {
  const auto expect_error = [](const nlohmann::json& j, const std::string& field) {
    GameConfig c = preset("peg3d");
    try {
      config::from_json(j, c, {"my.json", false});
      ADD_FAILURE() << "accepted " << j.dump();
    } catch (const config::ConfigError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_EQ(e.file(), "my.json");
      EXPECT_EQ(std::string(e.what()).rfind("my.json: " + field + ": ", 0), 0u) << e.what();
    }
  };
  expect_error({{"pursuer", {{"colour", "red"}}}}, "pursuer.colour");
  expect_error({{"dtt", 0.1}}, "dtt");
  expect_error({{"dt", "fast"}}, "dt");
  expect_error({{"evader", {{"observation", {{"sets", 2.5}}}}}}, "evader.observation.sets");
  expect_error({{"evader", {{"guard", {{"enabled", 1}}}}}}, "evader.guard.enabled");
  expect_error({{"pursuer", {{"policy", 3}}}}, "pursuer.policy");
  expect_error({{"pursuer", 3}}, "pursuer");
  expect_error({{"pursuers", {{{"speed", 2.0}}, {{"sped", 2.0}}}}}, "pursuers.1.sped");
}

TEST(GameConfig, PerAgentEntriesStartFromTheirRole) {
  GameConfig c = preset("peg3d");
  config::from_json(nlohmann::json{{"pursuers", {{{"speed", 2.0}}, {{"policy", "pn"}}}}}, c);
  ASSERT_EQ(c.pursuers.size(), 2u);
  AgentConfig expected = c.pursuer;
  expected.speed = 2.0;
  EXPECT_EQ(c.pursuers[0], expected);
  EXPECT_EQ(c.pursuers[1].policy, "pn");
  EXPECT_EQ(c.agent(Role::kPursuer, 1).policy, "pn");
  EXPECT_EQ(c.agent(Role::kPursuer, 2), c.pursuer);  // beyond the list: the role's settings
  EXPECT_EQ(c.agent(Role::kEvader, 0), c.evader);
  nlohmann::json image = config::to_json(c);
  config::apply_override(image, "pursuers.1.pn_gain=4");
  config::from_json(image, c);
  EXPECT_EQ(c.pursuers[1].pn_gain, 4.0);
}

TEST(GameConfig, AgentsInAGamesOrderArePursuersFirstThenEvaders) {
  GameConfig c = preset("peg3d");
  c.pursuers = {c.pursuer, c.pursuer};
  c.pursuers[1].speed = 1.7;
  c.evaders = {c.evader};
  c.evaders[0].radius = 0.4;
  // Two pursuers, then three evaders: agent 3 is evader 1, which has no entry of its own.
  EXPECT_EQ(role_at(1, 2), Role::kPursuer);
  EXPECT_EQ(role_at(2, 2), Role::kEvader);
  EXPECT_EQ(rank_at(1, 2), 1);
  EXPECT_EQ(rank_at(3, 2), 1);
  EXPECT_EQ(c.agent_at(1, 2).speed, 1.7);
  EXPECT_EQ(c.agent_at(2, 2).radius, 0.4);
  EXPECT_EQ(c.agent_at(3, 2), c.evader);
  EXPECT_EQ(c.agent_at(0, 0).radius, 0.4);  // no pursuers: agent 0 is evader 0
}

TEST(GameConfig, PresetsDifferWhereDocumented) {
  const GameConfig paper = preset("paper"), peg3d = preset("peg3d"), baseline = preset("baseline");
  EXPECT_EQ(paper.pursuer.observation.angles, AngleInputs::kAzimuth);
  EXPECT_EQ(paper.pursuer.structure, FaclStructure::kJoint);
  EXPECT_TRUE(paper.pursuer.motion_space);
  EXPECT_TRUE(paper.evader.motion_space);
  EXPECT_FALSE(paper.pursuer.guard.enabled);
  EXPECT_EQ(paper.pursuer.steering.polar_margin, 0.0);
  EXPECT_DOUBLE_EQ(paper.pursuer.speed, 1.1);
  EXPECT_DOUBLE_EQ(paper.evader.speed, 1.0);
  EXPECT_TRUE(peg3d.pursuer.motion_space);
  EXPECT_FALSE(peg3d.evader.motion_space);
  EXPECT_FALSE(baseline.pursuer.motion_space);
  EXPECT_EQ(baseline.pursuer.reward.kind, RewardKind::kDistanceOnly);
  EXPECT_EQ(baseline.evader, peg3d.evader);  // same opponent
  EXPECT_EQ(peg3d.team, TeamConfig{});       // one against one needs no team settings
  // robust: peg3d's agents, a pursuer less repelled by the walls that sees where the evader is heading and
  // learns an offset to pure pursuit, the team capture reward, one evader per pursuer (docs/learning.md); its
  // evader is peg3d's. (How it trains: experiment::trial_preset.)
  const GameConfig robust = preset("robust");
  TeamConfig team;
  team.capture_reward = CaptureReward::kTeam;
  team.pursuer_target = OpponentChoice::kAssigned;
  EXPECT_EQ(robust.team, team);
  AgentConfig pursuer = peg3d.pursuer;
  pursuer.reward.w_r = 1.0;
  pursuer.observation.opponent_heading = true;
  pursuer.action = FaclAction::kTargetLineOffset;
  EXPECT_EQ(robust.pursuer, pursuer);
  EXPECT_EQ(peg3d.pursuer.action, FaclAction::kHeadingChange);
  EXPECT_EQ(robust.evader, peg3d.evader);
  EXPECT_FALSE(peg3d.pursuer.observation.opponent_heading);
  EXPECT_THROW(preset("nope"), InputError);
}

TEST(GameConfig, InvalidFieldsAreRejectedByName) {
  struct Case {
    void (*mutate)(GameConfig&);
    const char* field;
  };
  const Case cases[] = {
      {[](GameConfig& c) { c.dt = 0.0; }, "dt"},
      {[](GameConfig& c) { c.time_limit = 0.05; }, "time_limit"},
      {[](GameConfig& c) { c.capture_distance = -1.0; }, "capture_distance"},
      {[](GameConfig& c) { c.pursuer.speed = 0.0; }, "pursuer.speed"},
      {[](GameConfig& c) { c.evader.speed = -1.0; }, "evader.speed"},
      {[](GameConfig& c) { c.pursuer.facl.critic_rate = 2.0; }, "pursuer.facl.critic_rate"},
      {[](GameConfig& c) { c.evader.observation.sets = 1; }, "evader.observation.sets"},
      {[](GameConfig& c) { c.pursuer.steering.polar_margin = 2.0; }, "pursuer.steering.polar_margin"},
      {[](GameConfig& c) { c.pursuer.steering.max_turn = 4.0; }, "pursuer.steering.max_turn"},
      {[](GameConfig& c) { c.pursuer.guard.warn_distance = 0.1; }, "pursuer.guard.warn_distance"},
      // Whether a policy plays its role is the players' registry's check (tests/players/registry_test.cpp); here, only
      // that it is a name.
      {[](GameConfig& c) { c.evader.policy = "Pure Pursuit"; }, "evader.policy"},
      {[](GameConfig& c) { c.pursuer.policy = ""; }, "pursuer.policy"},
      {[](GameConfig& c) { c.pursuer.reward.w_a = std::nan(""); }, "pursuer.reward.w_a"},
      {[](GameConfig& c) { c.pursuer.structure = FaclStructure::kPerAngle, c.pursuer.observation.angles = AngleInputs::kAzimuth; },
       "pursuer.structure"},
      {[](GameConfig& c) { c.pursuers = {c.pursuer, c.pursuer}, c.pursuers[1].radius = 0.0; }, "pursuers.1.radius"},
      {[](GameConfig& c) { c.evaders = {c.evader}, c.evaders[0].policy = std::string(65, 'a'); }, "evaders.0.policy"},
  };
  for (const Case& k : cases) {
    GameConfig c = preset("peg3d");
    k.mutate(c);
    try {
      c.validate();
      ADD_FAILURE() << k.field;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.parameter(), k.field) << e.what();
    }
  }
}

}  // namespace
}  // namespace peg3d::game
