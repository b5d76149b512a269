#include "fuzzy/facl_learner.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/validation.hpp"

namespace peg3d::fuzzy {
namespace {

RuleBase unit_rule_base(int sets = 2) { return RuleBase({TriangularPartition(0.0, 1.0, sets)}); }

TEST(Facl, OneStepEqualsTheHandComputedStep) {
  // One input on [0,1] with 2 sets; x = 0.25 gives Phi = (0.75, 0.25), x' = 1 gives Phi' = (0, 1).
  FaclConfig c{.actor_rate = 0.1, .critic_rate = 0.5, .discount = 0.9, .exploration_variance = 0.04};
  FaclTables learner(unit_rule_base(), 1, c);
  learner.actor_table()[0] = 0.2;
  learner.actor_table()[1] = -0.4;
  learner.critic_table()[0] = 1.0;
  learner.critic_table()[1] = 2.0;
  FiredRules now, next;
  const double x = 0.25, x_next = 1.0;
  learner.fire({&x, 1}, now);
  learner.fire({&x_next, 1}, next);
  double u = 0.0;
  learner.act(now, {&u, 1});
  EXPECT_NEAR(u, 0.75 * 0.2 + 0.25 * -0.4, 1e-15);  // 0.05
  EXPECT_NEAR(learner.value(now), 1.25, 1e-15);
  const double u_explored = 0.15;
  // delta = r + gamma V' - V = 0.3 + 0.9 * 2 - 1.25 = 0.85
  const double delta = learner.update(now, {&u, 1}, {&u_explored, 1}, 0.3, &next);
  EXPECT_NEAR(delta, 0.85, 1e-15);
  // actor: w += 0.1 * 0.85 * ((0.15 - 0.05) / 0.2) * Phi = 0.0425 Phi
  EXPECT_NEAR(learner.actor_table()[0], 0.2 + 0.0425 * 0.75, 1e-15);
  EXPECT_NEAR(learner.actor_table()[1], -0.4 + 0.0425 * 0.25, 1e-15);
  // critic: zeta += 0.5 * 0.85 * Phi = 0.425 Phi
  EXPECT_NEAR(learner.critic_table()[0], 1.0 + 0.425 * 0.75, 1e-15);
  EXPECT_NEAR(learner.critic_table()[1], 2.0 + 0.425 * 0.25, 1e-15);
}

TEST(Facl, TerminalSuccessorHasZeroValue) {
  FaclConfig c{.critic_rate = 0.5, .discount = 0.9};
  FaclTables learner(unit_rule_base(), 1, c);
  learner.critic_table()[0] = 3.0;
  learner.critic_table()[1] = 3.0;
  FiredRules now;
  const double x = 0.5;
  learner.fire({&x, 1}, now);
  const double u = 0.0;
  EXPECT_NEAR(learner.update(now, {&u, 1}, {&u, 1}, 1.0, nullptr), 1.0 - 3.0, 1e-15);
}

TEST(Facl, CriticConvergesToRewardOverOneMinusGamma) {
  // Constant reward r on random transitions: V(x) -> r / (1 - gamma) everywhere. Two inputs keep the
  // number of rules (25) small enough for every rule to converge quickly.
  const RuleBase rb({TriangularPartition(0, 35, 5), TriangularPartition(-M_PI, M_PI, 5)});
  FaclConfig c;  // paper defaults: gamma = 0.95, alpha_c = 0.05
  FaclTables learner(rb, 2, c);
  Rng rng(4);
  std::uniform_real_distribution<double> d(0, 35), a(-M_PI, M_PI);
  auto sample = [&](FiredRules& f) {
    const double x[2] = {d(rng), a(rng)};
    learner.fire(x, f);
  };
  FiredRules now, next;
  sample(now);
  const double r = 1.0, u[2] = {0, 0};
  for (int step = 0; step < 400000; ++step) {
    sample(next);
    learner.update(now, u, u, r, &next);
    std::swap(now, next);
  }
  for (int probe = 0; probe < 100; ++probe) {
    sample(now);
    EXPECT_NEAR(learner.value(now), r / (1.0 - c.discount), 1e-3);
  }
}

TEST(Facl, ActorMovesTowardTheRewardedAction) {
  // One state, terminal transitions, reward -(u' - 0.5)^2: exploration that lands nearer 0.5 than the critic
  // expects has delta > 0 and pulls the actor towards it.
  FaclConfig c{.actor_rate = 0.02, .critic_rate = 0.1, .discount = 0.0, .exploration_variance = 0.01};
  FaclTables learner(unit_rule_base(), 1, c);
  Exploration explore(c.exploration_variance, 21);
  FiredRules f;
  const double x = 0.3;
  learner.fire({&x, 1}, f);
  double u = 0, u_explored = 0;
  for (int step = 0; step < 20000; ++step) {
    explore.act(learner, f, {&u, 1}, {&u_explored, 1});
    learner.update(f, {&u, 1}, {&u_explored, 1}, -(u_explored - 0.5) * (u_explored - 0.5), nullptr);
  }
  learner.act(f, {&u, 1});
  EXPECT_NEAR(u, 0.5, 0.05);
}

TEST(Facl, ExplorationNoiseHasTheConfiguredVarianceAndIsSeeded) {
  FaclConfig c{.exploration_variance = 0.01};
  const FaclTables tables(unit_rule_base(), 2, c);
  Exploration a(c.exploration_variance, 77), b(c.exploration_variance, 77);
  FiredRules f;
  const double x = 0.5;
  tables.fire({&x, 1}, f);
  double u[2], ua[2], ub[2], sum = 0, sum_sq = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    a.act(tables, f, u, ua);
    b.act(tables, f, u, ub);
    ASSERT_EQ(ua[0], ub[0]);
    ASSERT_EQ(ua[1], ub[1]);
    sum += ua[0] - u[0];
    sum_sq += (ua[0] - u[0]) * (ua[0] - u[0]);
  }
  EXPECT_NEAR(sum / n, 0.0, 5e-4);             // standard error 0.1 / sqrt(n) = 2.2e-4
  EXPECT_NEAR(sum_sq / n, 0.01, 2e-4);          // standard error of the variance ~ 0.01 sqrt(2/n) = 3.2e-5
}

TEST(Facl, ActingReadsOnlyTheTables) {
  // Two explorers over one const table set: the greedy action is the same for both and the tables do not
  // change, so trained tables can be shared between threads for evaluation.
  FaclTables tables(unit_rule_base(), 1, FaclConfig{});
  tables.actor_table()[0] = 0.4;
  tables.actor_table()[1] = -0.2;
  const std::vector<double> before(tables.actor_table().begin(), tables.actor_table().end());
  FiredRules f;
  const double x = 0.75;
  tables.fire({&x, 1}, f);
  Exploration a(0.01, 1), b(0.01, 2);
  double ua = 0, ub = 0, ea = 0, eb = 0;
  a.act(tables, f, {&ua, 1}, {&ea, 1});
  b.act(tables, f, {&ub, 1}, {&eb, 1});
  EXPECT_EQ(ua, ub);
  EXPECT_NEAR(ua, 0.25 * 0.4 + 0.75 * -0.2, 1e-15);
  EXPECT_NE(ea, eb);  // different seeds, different noise
  EXPECT_EQ(std::vector<double>(tables.actor_table().begin(), tables.actor_table().end()), before);
}

TEST(Facl, RejectsInvalidParameters) {
  struct Case { FaclConfig config; const char* name; };
  const double nan = std::nan("");
  for (const Case& c : {Case{{.actor_rate = 0.0}, "facl.actor_rate"}, Case{{.actor_rate = 1.5}, "facl.actor_rate"},
                        Case{{.critic_rate = -0.1}, "facl.critic_rate"}, Case{{.critic_rate = nan}, "facl.critic_rate"},
                        Case{{.discount = 1.0}, "facl.discount"}, Case{{.discount = -0.5}, "facl.discount"},
                        Case{{.exploration_variance = 0.0}, "facl.exploration_variance"},
                        Case{{.initial_actor = INFINITY}, "facl.initial_actor"}}) {
    try {
      FaclTables(unit_rule_base(), 2, c.config);
      ADD_FAILURE() << c.name;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.parameter(), c.name) << e.what();
    }
  }
  EXPECT_THROW(FaclTables(unit_rule_base(), 0, FaclConfig{}), InvalidParameter);
}

}  // namespace
}  // namespace peg3d::fuzzy
