#include "fuzzy/rule_base.hpp"

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

// Sparse firing as the general loop does it, input by input: the reference the unrolled four- and six-input
// paths must match bit for bit.
void fire_input_by_input(const RuleBase& rb, std::span<const double> x, FiredRules& out) {
  std::vector<int> stride(std::size_t(rb.inputs()), 1);
  for (int i = rb.inputs() - 2; i >= 0; --i) stride[std::size_t(i)] = stride[std::size_t(i + 1)] * rb.input(i + 1).sets();
  out.count = 1;
  out.rule[0] = 0;
  out.strength[0] = 1.0;
  for (int i = 0; i < rb.inputs(); ++i) {
    const Activation a = rb.input(i).activate(x[std::size_t(i)]);
    const int n = out.count;
    for (int e = 0; e < n; ++e) {
      const int r = out.rule[e] + a.lower * stride[std::size_t(i)];
      const double w = out.strength[e];
      out.rule[e] = r;
      out.strength[e] = w * (1.0 - a.t);
      out.rule[n + e] = r + stride[std::size_t(i)];
      out.strength[n + e] = w * a.t;
    }
    out.count = 2 * n;
  }
  double sum = 0.0;
  for (int e = 0; e < out.count; ++e) sum += out.strength[e];
  const double inv = 1.0 / sum;
  for (int e = 0; e < out.count; ++e) out.strength[e] *= inv;
}

TEST(RuleBase, EveryInputCountFiresTheBitsOfTheInputByInputLoop) {
  Rng rng(17);
  std::uniform_real_distribution<double> u(-4.0, 40.0);
  for (int inputs = 1; inputs <= 8; ++inputs) {
    std::vector<TriangularPartition> parts;
    for (int i = 0; i < inputs; ++i) parts.emplace_back(i % 2 ? -M_PI : 0.0, i % 2 ? M_PI : 35.0, 3 + i % 4);
    const RuleBase rb(parts);
    for (int trial = 0; trial < 2000; ++trial) {
      std::vector<double> x(static_cast<std::size_t>(inputs));
      for (double& v : x) v = trial % 7 == 0 ? std::round(u(rng)) : u(rng);  // also on set centres and edges
      FiredRules got, want;
      rb.fire(x, got);
      fire_input_by_input(rb, x, want);
      ASSERT_EQ(got.count, want.count);
      for (int e = 0; e < want.count; ++e) {
        ASSERT_EQ(got.rule[e], want.rule[e]) << inputs << " inputs, entry " << e;
        ASSERT_EQ(std::memcmp(&got.strength[e], &want.strength[e], sizeof(double)), 0) << inputs << " inputs, entry " << e;
      }
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
