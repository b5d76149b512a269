#include "fuzzy/facl_learner.hpp"

#include <cassert>
#include <cmath>

#include "core/validation.hpp"

namespace peg3d::fuzzy {

void FaclConfig::validate(const std::string& prefix) const {
  require_in_range(prefix + ".actor_rate", actor_rate, 0.0, 1.0, /*lo_open=*/true);
  require_in_range(prefix + ".critic_rate", critic_rate, 0.0, 1.0, /*lo_open=*/true);
  require_in_range(prefix + ".discount", discount, 0.0, 1.0, false, /*hi_open=*/true);
  require_positive(prefix + ".exploration_variance", exploration_variance);
  require_finite(prefix + ".initial_actor", initial_actor);
  require_finite(prefix + ".initial_critic", initial_critic);
}

FaclLearner::FaclLearner(RuleBase rules, int actions, const FaclConfig& config, std::uint64_t seed)
    : rules_(std::move(rules)), actions_(actions), config_(config) {
  config_.validate();
  require_at_least("facl.actions", actions, 1);
  sigma_ = std::sqrt(config_.exploration_variance);
  actor_.assign(static_cast<std::size_t>(rules_.rules()) * actions_, config_.initial_actor);
  critic_.assign(rules_.rules(), config_.initial_critic);
  noise_ = std::normal_distribution<double>(0.0, sigma_);
  reseed(seed);
}

void FaclLearner::reseed(std::uint64_t seed) {
  rng_.seed(seed);
  noise_.reset();  // drop any cached second normal deviate
}

void FaclLearner::act(const FiredRules& fired, std::span<double> u) const {
  assert(static_cast<int>(u.size()) == actions_);
  for (int j = 0; j < actions_; ++j) u[j] = ts_output(fired, actor_, actions_, j);
}

void FaclLearner::act_exploring(const FiredRules& fired, std::span<double> u, std::span<double> u_explored) {
  act(fired, u);
  for (int j = 0; j < actions_; ++j) u_explored[j] = u[j] + noise_(rng_);
}

double FaclLearner::update(const FiredRules& now, std::span<const double> u, std::span<const double> u_explored,
                           double reward, const FiredRules* next) {
  const double v_now = value(now);
  const double v_next = next != nullptr ? value(*next) : 0.0;
  const double delta = reward + config_.discount * v_next - v_now;
  // The paper's partial derivatives (eq. 12, 14) are the normalised strengths Phi_l themselves.
  const double actor_step = config_.actor_rate * delta / sigma_;
  const double critic_step = config_.critic_rate * delta;
  for (int i = 0; i < now.count; ++i) {
    const double phi = now.strength[i];
    const int l = now.rule[i];
    for (int j = 0; j < actions_; ++j) actor_[l * actions_ + j] += actor_step * (u_explored[j] - u[j]) * phi;
    critic_[l] += critic_step * phi;
  }
  return delta;
}

}  // namespace peg3d::fuzzy
