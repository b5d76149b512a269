#include "game/reward.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace peg3d::game {
namespace {

// Paper defaults: alpha_r = 10, beta_a = 5, gamma_s = 20, w_r = 5, w_a = 10.
TEST(Reward, PursuerTermsMatchTheHandComputedValues) {
  const RewardConfig c;
  // d_PE 10 -> 9.9 (dd = -0.1), d_O 3 -> 2.95 (dd = -0.05), no capture:
  //   r_O = 1 - exp(-10 * -0.05) = 1 - e^0.5 = -0.6487212707
  //   r_PE = exp(-5 * -0.1) - 1 = e^0.5 - 1 = 0.6487212707
  //   r = 5 r_O + 10 r_PE = 3.2436063535
  const RewardTerms t = reward(Role::kPursuer, c, {10.0, 9.9, 3.0, 2.95, false, false}, 0.21);
  EXPECT_NEAR(t.obstacle, 1.0 - std::exp(0.5), 1e-12);
  EXPECT_NEAR(t.target, std::exp(0.5) - 1.0, 1e-12);
  EXPECT_EQ(t.success, 0.0);
  EXPECT_NEAR(t.total, 5 * (1 - std::exp(0.5)) + 10 * (std::exp(0.5) - 1), 1e-12);
  EXPECT_NEAR(t.total, 3.2436063535, 1e-9);
}

TEST(Reward, CaptureAddsGammaSForThePursuerAndSubtractsItForTheEvader) {
  const RewardConfig c;
  const RewardInputs in{1.05, 0.95, 5.0, 5.0, true, false};  // d_O capped at both ends: r_O = 0
  const RewardTerms p = reward(Role::kPursuer, c, in, 0.21);
  const RewardTerms e = reward(Role::kEvader, c, in, 0.21);
  EXPECT_EQ(p.success, 20.0);
  EXPECT_EQ(e.success, -20.0);
  EXPECT_NEAR(p.total, 10 * (std::exp(0.5) - 1) + 20, 1e-12);
}

TEST(Reward, EvaderInversionNegateAndMirror) {
  RewardConfig c;
  const RewardInputs opening{10.0, 10.1, 5.0, 5.0, false, false};  // dd = +0.1
  c.inversion = EvaderInversion::kNegate;
  EXPECT_NEAR(reward(Role::kEvader, c, opening, 0.21).target, 1.0 - std::exp(-0.5), 1e-12);  // 0.3935
  c.inversion = EvaderInversion::kMirror;
  EXPECT_NEAR(reward(Role::kEvader, c, opening, 0.21).target, std::exp(0.5) - 1.0, 1e-12);   // 0.6487
  // Either way the evader gains by opening the distance and the pursuer loses.
  EXPECT_LT(reward(Role::kPursuer, c, opening, 0.21).target, 0.0);
}

TEST(Reward, DistanceOnlyBaselineIsTheNormalisedDistanceChange) {
  RewardConfig c;
  c.kind = RewardKind::kDistanceOnly;
  const RewardInputs closing{10.0, 9.79, 1.0, 0.5, true, false};
  EXPECT_NEAR(reward(Role::kPursuer, c, closing, 0.21).total, 1.0, 1e-12);  // closed at the maximal rate
  EXPECT_NEAR(reward(Role::kEvader, c, closing, 0.21).total, -1.0, 1e-12);
}

TEST(Reward, CollisionPenaltyIsSubtracted) {
  RewardConfig c;
  c.collision_penalty = 7.0;
  const RewardInputs still{10.0, 10.0, 2.0, 2.0, false, true};
  EXPECT_NEAR(reward(Role::kPursuer, c, still, 0.21).total, -7.0, 1e-12);
}

}  // namespace
}  // namespace peg3d::game
