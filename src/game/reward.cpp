#include "game/reward.hpp"

#include <cmath>

namespace peg3d::game {

RewardTerms reward(Role role, const RewardConfig& c, const RewardInputs& in, double max_closing_step) {
  RewardTerms t;
  const double dd_target = in.target_after - in.target_before;
  const double sign = role == Role::kPursuer ? 1.0 : -1.0;
  if (c.kind == RewardKind::kDistanceOnly) {
    t.target = -sign * dd_target / max_closing_step;
    t.total = t.target;
  } else {
    t.obstacle = 1.0 - std::exp(-c.alpha_r * (in.obstacle_after - in.obstacle_before));
    if (role == Role::kPursuer) {
      t.target = std::exp(-c.beta_a * dd_target) - 1.0;
    } else if (c.inversion == EvaderInversion::kNegate) {
      t.target = 1.0 - std::exp(-c.beta_a * dd_target);
    } else {
      t.target = std::exp(c.beta_a * dd_target) - 1.0;
    }
    t.success = in.captures > 0 ? sign * c.gamma_s * in.captures : 0.0;
    t.total = c.w_r * t.obstacle + c.w_a * t.target + t.success;
  }
  if (in.collided) t.total -= c.collision_penalty;
  return t;
}

}  // namespace peg3d::game
