#pragma once
// Fuzzy actor-critic learning (paper section 3.2, eq. 7-14). Actor and critic are zero-order TS systems over
// the same rule base:
//   actor   u_j = sum_l Phi_l w_lj            (one output per steering angle)
//   critic  V   = sum_l Phi_l zeta_l
//   TD      delta = r + gamma V(x') - V(x)    (V(terminal) = 0)
//   explore u'_j = u_j + N(0, sigma^2)
//   actor   w_lj    += alpha_a delta ((u'_j - u_j) / sigma) Phi_l
//   critic  zeta_l  += alpha_c delta Phi_l
// FaclTables holds what is learned (shareable, const while acting); Exploration holds the noise engine of one
// learning agent.

#include <concepts>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "core/config_fields.hpp"
#include "core/random.hpp"
#include "fuzzy/rule_base.hpp"

namespace peg3d::fuzzy {

/// FACL hyper-parameters; defaults are the paper's (section 4).
struct FaclConfig {
  double actor_rate = 0.001;           ///< alpha_a, in (0, 1]
  double critic_rate = 0.05;           ///< alpha_c, in (0, 1]
  double discount = 0.95;              ///< gamma, in [0, 1)
  double exploration_variance = 0.01;  ///< sigma^2 of the Gaussian exploration noise, rad^2, > 0
  double initial_actor = 0.0;          ///< initial consequent of every actor rule (output units), finite
  double initial_critic = 0.0;         ///< initial consequent of every critic rule, finite

  /// Throws InvalidParameter naming the field, e.g. "facl.actor_rate" (prefix "facl").
  void validate(const std::string& prefix = "facl") const;
  bool operator==(const FaclConfig&) const = default;
};

/// The fields of a FaclConfig (core/config_fields.hpp).
template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, FaclConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.number("actor_rate", c.actor_rate, Range::open_closed(0, 1), "", "alpha_a, the actor's learning rate (paper 0.001)");
  v.number("critic_rate", c.critic_rate, Range::open_closed(0, 1), "", "alpha_c, the critic's learning rate (paper 0.05)");
  v.number("discount", c.discount, Range::closed_open(0, 1), "", "gamma, the TD discount (paper 0.95)");
  v.number("exploration_variance", c.exploration_variance, Range::positive(), "rad^2",
           "sigma^2 of the Gaussian exploration noise added to each output (paper 0.01)");
  v.number("initial_actor", c.initial_actor, Range::any(), "rad", "initial consequent of every actor rule");
  v.number("initial_critic", c.initial_critic, Range::any(), "", "initial consequent of every critic rule");
}

/// The learned part of FACL: the actor and critic consequents over one rule base. Acting and valuing are
/// const and touch nothing else, so one trained set of tables can serve evaluations on any number of threads
/// at once; update() is the only writer (training owns its tables alone).
class FaclTables {
 public:
  /// 1 or 2 actor outputs (one per steering angle). Throws InvalidParameter on a bad configuration.
  FaclTables(RuleBase rules, int actions, const FaclConfig& config);

  const RuleBase& rules() const { return rules_; }
  const FaclConfig& config() const { return config_; }
  int actions() const { return actions_; }

  /// Fires the rule base at x (no allocation).
  void fire(std::span<const double> x, FiredRules& out) const { rules_.fire(x, out); }

  /// Greedy action u = actor(x).
  void act(const FiredRules& fired, std::span<double> u) const;
  /// Critic estimate V(x).
  double value(const FiredRules& fired) const { return ts_output(fired, critic_, 1, 0); }

  /// One TD update after taking u_explored in `now` and receiving `reward`; `next` is the successor's
  /// firing or nullptr when the successor is terminal. Returns delta. V(now) and V(next) are both taken
  /// before the update.
  double update(const FiredRules& now, std::span<const double> u, std::span<const double> u_explored,
                double reward, const FiredRules* next);

  /// Consequent tables, rule-major (actor: rules() x actions()). Exposed for saving and loading policies.
  std::span<double> actor_table() { return actor_; }
  std::span<const double> actor_table() const { return actor_; }
  std::span<double> critic_table() { return critic_; }
  std::span<const double> critic_table() const { return critic_; }

 private:
  RuleBase rules_;
  int actions_;
  FaclConfig config_;
  double sigma_;
  std::vector<double> actor_;
  std::vector<double> critic_;
};

/// Gaussian exploration noise N(0, sigma^2) from an owned, seeded engine: the same seed gives the same noise.
/// It belongs to whoever explores (one per learning agent and output channel), never to the shared tables.
class Exploration {
 public:
  Exploration(double variance, std::uint64_t seed);

  /// Greedy action of `tables` and the explored action u' = u + N(0, sigma^2) per output.
  void act(const FaclTables& tables, const FiredRules& fired, std::span<double> u, std::span<double> u_explored);
  double sample() { return noise_(rng_); }
  /// Restarts the noise stream.
  void reseed(std::uint64_t seed);

 private:
  Rng rng_;
  std::normal_distribution<double> noise_;
};

}  // namespace peg3d::fuzzy
