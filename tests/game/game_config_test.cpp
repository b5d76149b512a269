#include "game/game_config.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/validation.hpp"

namespace peg3d::game {
namespace {

TEST(GameConfig, JsonRoundTripKeepsEveryField) {
  for (const char* name : {"peg3d", "paper", "baseline"}) {
    GameConfig c = preset(name);
    c.pursuer.facl.actor_rate = 0.0123;
    c.evader.guard.warn_distance = 3.5;
    c.initial_heading = InitialHeading::kRandom;
    const nlohmann::json j = c;
    const GameConfig back = j.get<GameConfig>();
    EXPECT_EQ(nlohmann::json(back), j) << name;
  }
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
  EXPECT_EQ(nlohmann::json(baseline.evader), nlohmann::json(peg3d.evader));  // same opponent
  EXPECT_THROW(preset("nope"), std::invalid_argument);
}

TEST(GameConfig, InvalidFieldsAreRejectedByName) {
  struct Case {
    void (*mutate)(GameConfig&);
    const char* field;
  };
  const Case cases[] = {
      {[](GameConfig& c) { c.dt = 0.0; }, "dt"},
      {[](GameConfig& c) { c.capture_distance = -1.0; }, "capture_distance"},
      {[](GameConfig& c) { c.pursuer.speed = 0.0; }, "pursuer.speed"},
      {[](GameConfig& c) { c.evader.speed = -1.0; }, "evader.speed"},
      {[](GameConfig& c) { c.pursuer.facl.critic_rate = 2.0; }, "pursuer.facl.critic_rate"},
      {[](GameConfig& c) { c.evader.observation.sets = 1; }, "evader.observation.sets"},
      {[](GameConfig& c) { c.pursuer.steering.polar_margin = 2.0; }, "pursuer.steering.polar_margin"},
      {[](GameConfig& c) { c.pursuer.guard.warn_distance = 0.1; }, "pursuer.guard.warn_distance"},
      {[](GameConfig& c) { c.evader.policy = "teleport"; }, "evader.policy"},
      {[](GameConfig& c) { c.pursuer.reward.w_a = std::nan(""); }, "pursuer.reward.w_a"},
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

TEST(GameConfig, UnknownEnumNamesAreErrors) {
  nlohmann::json j = preset("peg3d");
  j["pursuer"]["observation"]["angles"] = "sideways";
  EXPECT_THROW(j.get<GameConfig>(), InvalidParameter);
}

}  // namespace
}  // namespace peg3d::game
