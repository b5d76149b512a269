#pragma once
// Rewards (paper eq. 15-18). For the pursuer, with dd = d(t+1) - d(t):
//   r_O  = 1 - exp(-alpha_r dd_O)      repulsion from the nearest obstacle (eq. 15)
//   r_PE = exp(-beta_a dd_PE) - 1      attraction to the evader (eq. 16)
//   r_s  = gamma_s g                   capture (eq. 17)
//   r    = w_r r_O + w_a r_PE + r_s    (eq. 18)
// The evader's r_PE and r_s are "inverted" (EvaderInversion); r_O has the same form for both.

#include "game/game_config.hpp"

namespace peg3d::game {

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
