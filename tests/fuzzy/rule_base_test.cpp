#include "fuzzy/rule_base.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "core/random.hpp"
#include "core/validation.hpp"

namespace peg3d::fuzzy {
namespace {

RuleBase paper_rule_base() {
  // The paper's 4 inputs x 5 sets: distances over [0, 35] m, angles over [-pi, pi] rad.
  return RuleBase({TriangularPartition(0, 35, 5), TriangularPartition(-M_PI, M_PI, 5), TriangularPartition(0, 35, 5),
                   TriangularPartition(-M_PI, M_PI, 5)});
}

TEST(RuleBase, PaperConfigurationHas625Rules) { EXPECT_EQ(paper_rule_base().rules(), 625); }

TEST(RuleBase, SparseFiringVisitsAtMostTwoToTheNRules) {
  const RuleBase rb = paper_rule_base();
  FiredRules f;
  const double x[4] = {10.0, 0.3, 2.0, -1.0};
  rb.fire(x, f);
  EXPECT_EQ(f.count, 16);
  double sum = 0.0;
  for (int i = 0; i < f.count; ++i) sum += f.strength[i];
  EXPECT_NEAR(sum, 1.0, 1e-15);
}

TEST(RuleBase, SparseAndDenseEvaluationAgree) {
  Rng rng(123);
  // Uneven set counts as well as the paper's, so strides are exercised.
  for (const RuleBase& rb : {paper_rule_base(),
                             RuleBase({TriangularPartition(-1, 2, 2), TriangularPartition(0, 1, 3),
                                       TriangularPartition(5, 9, 7)})}) {
    const int n = rb.inputs(), outputs = 2;
    std::vector<double> table(static_cast<std::size_t>(rb.rules()) * outputs);
    std::uniform_real_distribution<double> w(-1.0, 1.0);
    for (double& t : table) t = w(rng);
    std::vector<double> phi(rb.rules()), x(n);
    FiredRules f;
    for (int trial = 0; trial < 5000; ++trial) {
      for (int i = 0; i < n; ++i) {
        const double span = rb.input(i).hi() - rb.input(i).lo();
        x[i] = std::uniform_real_distribution<double>(rb.input(i).lo() - 0.1 * span, rb.input(i).hi() + 0.1 * span)(rng);
      }
      rb.fire(x, f);
      rb.fire_dense(x, phi);
      for (int i = 0; i < f.count; ++i) ASSERT_NEAR(f.strength[i], phi[f.rule[i]], 1e-12);
      for (int j = 0; j < outputs; ++j) {
        ASSERT_NEAR(ts_output(f, table, outputs, j), ts_output_dense(phi, table, outputs, j), 1e-12);
      }
    }
  }
}

// The analytic firing of n inputs: input i activates sets k_i (weight 1 - t_i) and k_i + 1 (weight t_i), and
// the rule of sets (s_0, ..., s_{n-1}) fires with the product of its inputs' weights (they sum to 1, so
// normalising changes nothing). Partitions of width 0.5 and inputs at k + t with t in eighths make every
// weight and product exact in binary: fire() must give each of the 2^n rules exactly its product, for every
// input count 1 to 8, including inputs on a set's centre (t = 0) and clamped beyond either end.
TEST(RuleBase, EveryInputCountFiresEachRuleWithTheProductOfItsMemberships) {
  Rng rng(17);
  for (int inputs = 1; inputs <= 8; ++inputs) {
    std::vector<TriangularPartition> parts;
    std::vector<int> sets;
    for (int i = 0; i < inputs; ++i) {
      sets.push_back(2 + (i * 3) % 5);  // 2 to 6 sets
      const double lo = i % 2 ? -1.0 : 3.0;
      parts.emplace_back(lo, lo + 0.5 * (sets.back() - 1), sets.back());
    }
    const RuleBase rb(parts);
    std::vector<int> stride(std::size_t(inputs), 1);
    for (int i = inputs - 2; i >= 0; --i) stride[std::size_t(i)] = stride[std::size_t(i + 1)] * sets[std::size_t(i + 1)];
    for (int trial = 0; trial < 300; ++trial) {
      const auto count = static_cast<std::size_t>(inputs);
      std::vector<double> x(count), t(count);
      std::vector<int> k(count);
      for (int i = 0; i < inputs; ++i) {
        const int n = sets[std::size_t(i)];
        const int where = std::uniform_int_distribution<int>(0, 9)(rng);
        if (where == 0) {  // clamped below: the first set alone
          x[std::size_t(i)] = parts[std::size_t(i)].lo() - 7.25, k[std::size_t(i)] = 0, t[std::size_t(i)] = 0.0;
        } else if (where == 1) {  // clamped above: the last set alone
          x[std::size_t(i)] = parts[std::size_t(i)].hi() + 3.5, k[std::size_t(i)] = n - 2, t[std::size_t(i)] = 1.0;
        } else {
          k[std::size_t(i)] = std::uniform_int_distribution<int>(0, n - 2)(rng);
          t[std::size_t(i)] = std::uniform_int_distribution<int>(0, 7)(rng) / 8.0;  // 0: on set k's centre
          x[std::size_t(i)] = parts[std::size_t(i)].lo() + 0.5 * (k[std::size_t(i)] + t[std::size_t(i)]);
        }
      }
      FiredRules f;
      rb.fire(x, f);
      ASSERT_EQ(f.count, 1 << inputs);
      std::vector<int> seen;
      for (int e = 0; e < f.count; ++e) {
        // Which set each input contributes to this rule, read back from the mixed-radix index.
        double product = 1.0;
        int rest = f.rule[e];
        for (int i = 0; i < inputs; ++i) {
          const int s_i = rest / stride[std::size_t(i)];
          rest %= stride[std::size_t(i)];
          const int b = s_i - k[std::size_t(i)];
          ASSERT_TRUE(b == 0 || b == 1) << inputs << " inputs, rule " << f.rule[e] << ", input " << i;
          product *= b ? t[std::size_t(i)] : 1.0 - t[std::size_t(i)];
        }
        ASSERT_EQ(f.strength[e], product) << inputs << " inputs, rule " << f.rule[e];
        seen.push_back(f.rule[e]);
      }
      std::sort(seen.begin(), seen.end());
      ASSERT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end()) << inputs << " inputs: a rule fired twice";
    }
  }
}

TEST(RuleBase, RuleIndexIsMixedRadixWithInputZeroMostSignificant) {
  const RuleBase rb = paper_rule_base();
  const int sets[4] = {1, 2, 3, 4};
  EXPECT_EQ(rb.rule_index(sets), 1 * 125 + 2 * 25 + 3 * 5 + 4);
}

TEST(RuleBase, RejectsNoInputsAndTooManyInputs) {
  EXPECT_THROW(RuleBase({}), InvalidParameter);
  EXPECT_THROW(RuleBase(std::vector<TriangularPartition>(9, TriangularPartition(0, 1, 2))), InvalidParameter);
}

}  // namespace
}  // namespace peg3d::fuzzy
