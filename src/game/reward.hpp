#pragma once
// Rewards (paper eq. 15-18). For the pursuer, with dd = d(t+1) - d(t):
//   r_O  = 1 - exp(-alpha_r dd_O)      repulsion from the nearest obstacle (eq. 15)
//   r_PE = exp(-beta_a dd_PE) - 1      attraction to the evader (eq. 16)
//   r_s  = gamma_s g                   capture (eq. 17)
//   r    = w_r r_O + w_a r_PE + r_s    (eq. 18)
// The evader's r_PE and r_s are "inverted" (EvaderInversion); r_O has the same form for both.

#include <concepts>
#include <type_traits>

#include "core/config_fields.hpp"
#include "game/role.hpp"

namespace peg3d::game {

enum class RewardKind {
  kPotentialField,  ///< paper eq. (15)-(18): w_r r_O + w_a r_PE + r_s
  kDistanceOnly,    ///< baseline: the normalised change of d_PE, (d(t) - d(t+1)) / ((vP + vE) dt)
};
inline constexpr config::EnumNames<RewardKind, 2> kRewardKindNames{
    {{RewardKind::kPotentialField, "potential-field"}, {RewardKind::kDistanceOnly, "distance-only"}}};

/// How the paper's "inverted" terms are read for the evader.
enum class EvaderInversion {
  kNegate,  ///< r_E = -r_P term by term: 1 - exp(-beta dd), -gamma_s g (the repulsion form)
  kMirror,  ///< the sign of the argument flips: exp(beta dd) - 1, -gamma_s g
};
inline constexpr config::EnumNames<EvaderInversion, 2> kEvaderInversionNames{
    {{EvaderInversion::kNegate, "negate"}, {EvaderInversion::kMirror, "mirror"}}};

struct RewardConfig {
  RewardKind kind = RewardKind::kPotentialField;
  double alpha_r = 10.0;  ///< repulsion coefficient (1/m), >= 0 (paper 10)
  double beta_a = 5.0;    ///< attraction coefficient (1/m), >= 0 (paper 5)
  double gamma_s = 20.0;  ///< capture reward, >= 0 (paper 20)
  double w_r = 5.0;       ///< repulsion weight, >= 0 (paper 5)
  double w_a = 10.0;      ///< attraction weight, >= 0 (paper 10)
  EvaderInversion inversion = EvaderInversion::kNegate;
  double collision_penalty = 0.0;  ///< subtracted from the colliding agent's reward, >= 0 (paper: none)
  bool operator==(const RewardConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, RewardConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.choice("kind", c.kind, kRewardKindNames, "the paper's potential-field reward or the baseline's distance change");
  v.number("alpha_r", c.alpha_r, Range::non_negative(), "1/m", "repulsion coefficient of r_O, eq. 15 (paper 10)");
  v.number("beta_a", c.beta_a, Range::non_negative(), "1/m", "attraction coefficient of r_PE, eq. 16 (paper 5)");
  v.number("gamma_s", c.gamma_s, Range::non_negative(), "", "capture reward r_s, eq. 17 (paper 20)");
  v.number("w_r", c.w_r, Range::non_negative(), "", "weight of r_O, eq. 18 (paper 5)");
  v.number("w_a", c.w_a, Range::non_negative(), "", "weight of r_PE, eq. 18 (paper 10)");
  v.choice("inversion", c.inversion, kEvaderInversionNames, "how the evader's terms invert the pursuer's");
  v.number("collision_penalty", c.collision_penalty, Range::non_negative(), "",
           "subtracted from the reward of an agent that hits an obstacle (paper: none)");
}

/// The quantities one agent's reward depends on, over one step.
struct RewardInputs {
  double target_before = 0.0;    ///< d_PE(t), m
  double target_after = 0.0;     ///< d_PE(t+1), m
  double obstacle_before = 0.0;  ///< d_O(t), m (capped)
  double obstacle_after = 0.0;   ///< d_O(t+1), m (capped)
  int captures = 0;              ///< g_s: captures credited to this agent in this step (0 or 1 in a 1 v 1 game)
  bool collided = false;         ///< this agent hit an obstacle in this step
};

/// The separate terms, for logging and tests.
struct RewardTerms {
  double obstacle = 0.0;  ///< r_O (unweighted)
  double target = 0.0;    ///< r_PE for the pursuer, its inversion for the evader (unweighted)
  double success = 0.0;   ///< r_s, already scaled by gamma_s, signed for the role
  double total = 0.0;     ///< the weighted sum minus any collision penalty
};

/// max_closing_step: the largest possible change of d_PE in one step, (vP + vE) dt, m, used by the
/// distance-only baseline to normalise its reward to [-1, 1].
RewardTerms reward(Role role, const RewardConfig& config, const RewardInputs& in, double max_closing_step);

}  // namespace peg3d::game
