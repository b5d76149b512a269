#include "fuzzy/facl_learner.hpp"

#include <cassert>
#include <cmath>

#include "core/validation.hpp"

namespace peg3d::fuzzy {

void FaclConfig::validate(const std::string& prefix) const { config::validate(*this, prefix + "."); }

FaclTables::FaclTables(RuleBase rules, int actions, const FaclConfig& config)
    : rules_(std::move(rules)), actions_(actions), config_(config) {
  config_.validate();
  require_at_least("facl.actions", actions, 1);
  if (actions > 2) throw InvalidParameter("facl.actions", std::to_string(actions), "must be 1 or 2 (one per steering angle)");
  sigma_ = std::sqrt(config_.exploration_variance);
  actor_.assign(static_cast<std::size_t>(rules_.rules()) * actions_, config_.initial_actor);
  critic_.assign(rules_.rules(), config_.initial_critic);
}

void FaclTables::act(const FiredRules& fired, std::span<double> u) const {
  assert(static_cast<int>(u.size()) == actions_);
  for (int j = 0; j < actions_; ++j) u[j] = ts_output(fired, actor_, actions_, j);
}

double FaclTables::update(const FiredRules& now, std::span<const double> u, std::span<const double> u_explored,
                          double reward, const FiredRules* next) {
  const double v_now = value(now);
  const double v_next = next != nullptr ? value(*next) : 0.0;
  const double delta = reward + config_.discount * v_next - v_now;
  // The paper's partial derivatives (eq. 12, 14) are the normalised strengths Phi_l themselves. Each output's
  // factor alpha_a delta (u'_j - u_j) / sigma is the same for every rule: computed once (the same product, so
  // the same bits, as writing it out in the loop).
  const double actor_step = config_.actor_rate * delta / sigma_;
  const double critic_step = config_.critic_rate * delta;
  assert(actions_ <= 2);
  const double g0 = actor_step * (u_explored[0] - u[0]);
  if (actions_ == 1) {
    for (int i = 0; i < now.count; ++i) {
      const double phi = now.strength[i];
      const int l = now.rule[i];
      actor_[std::size_t(l)] += g0 * phi;
      critic_[std::size_t(l)] += critic_step * phi;
    }
  } else {
    const double g1 = actor_step * (u_explored[1] - u[1]);
    for (int i = 0; i < now.count; ++i) {
      const double phi = now.strength[i];
      const int l = now.rule[i];
      actor_[std::size_t(2 * l)] += g0 * phi;
      actor_[std::size_t(2 * l + 1)] += g1 * phi;
      critic_[std::size_t(l)] += critic_step * phi;
    }
  }
  return delta;
}

Exploration::Exploration(double variance, std::uint64_t seed) : noise_(0.0, std::sqrt(variance)) {
  require_positive("facl.exploration_variance", variance);
  reseed(seed);
}

void Exploration::reseed(std::uint64_t seed) {
  rng_.seed(seed);
  noise_.reset();  // drop any cached second normal deviate
}

void Exploration::act(const FaclTables& tables, const FiredRules& fired, std::span<double> u,
                      std::span<double> u_explored) {
  tables.act(fired, u);
  for (int j = 0; j < tables.actions(); ++j) u_explored[j] = u[j] + noise_(rng_);
}

}  // namespace peg3d::fuzzy
