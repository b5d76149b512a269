#include "results/statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/validation.hpp"

namespace peg3d::results {
namespace {

// R prints 7 significant digits; compare to that.
constexpr double kRTol = 5e-7;

// R's `sleep` data set (Student 1908): extra hours of sleep with drug 1 and drug 2 on the same 10 patients.
// The differences are -1.2 -2.4 -1.3 -1.3 0 -1 -1.8 -0.8 -4.6 -1.4: one zero and one tie (|-1.3| twice).
const std::vector<double> kSleep1 = {0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
const std::vector<double> kSleep2 = {1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};

// Hollander & Wolfe (1973, p. 29), the example in R's ?wilcox.test: depression scale before (x) and after
// (y) a tranquilizer. Differences have no ties and no zeros.
const std::vector<double> kDepressionX = {1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
const std::vector<double> kDepressionY = {0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29};

TEST(ResultsStatistics, CriticalValuesMatchR) {
  EXPECT_NEAR(normal_critical_value(0.95), 1.959964, 1e-6);  // qnorm(0.975)
  EXPECT_NEAR(t_critical_value(0.95, 9), 2.262157, 1e-6);    // qt(0.975, 9)
  EXPECT_NEAR(t_critical_value(0.95, 4), 2.776445, 1e-6);    // qt(0.975, 4)
}

TEST(ResultsStatistics, WilsonIntervalEightOfTen) {
  // prop.test(8, 10, correct = FALSE)$conf.int: 0.4901625 0.9433178
  const ProportionInterval w = wilson_interval(8, 10);
  EXPECT_DOUBLE_EQ(w.rate, 0.8);
  EXPECT_NEAR(w.lo, 0.4901625, kRTol);
  EXPECT_NEAR(w.hi, 0.9433178, kRTol);
}

TEST(ResultsStatistics, WilsonIntervalAllSuccessesReachesOne) {
  // n/n: closed form lo = n / (n + z^2) = 20 / (20 + 1.959964^2) = 0.8388748 (prop.test(20, 20, correct = FALSE))
  const ProportionInterval w = wilson_interval(20, 20);
  EXPECT_DOUBLE_EQ(w.rate, 1.0);
  EXPECT_NEAR(w.lo, 0.8388748, kRTol);
  EXPECT_EQ(w.hi, 1.0);
}

TEST(ResultsStatistics, WilsonIntervalNoSuccessesStartsAtZero) {
  // 0/n: closed form hi = z^2 / (n + z^2) = 0.1611252 (prop.test(0, 20, correct = FALSE))
  const ProportionInterval w = wilson_interval(0, 20);
  EXPECT_EQ(w.rate, 0.0);
  EXPECT_EQ(w.lo, 0.0);
  EXPECT_NEAR(w.hi, 0.1611252, kRTol);
}

TEST(ResultsStatistics, WilsonIntervalHonoursConfidence) {
  // prop.test(8, 10, correct = FALSE, conf.level = 0.9)$conf.int: 0.5407928 0.9314420
  const ProportionInterval w = wilson_interval(8, 10, 0.90);
  EXPECT_NEAR(w.lo, 0.5407928, kRTol);
  EXPECT_NEAR(w.hi, 0.9314420, kRTol);
}

TEST(ResultsStatistics, WilsonIntervalWithoutTrialsIsUninformative) {
  const ProportionInterval w = wilson_interval(0, 0);
  EXPECT_TRUE(std::isnan(w.rate));
  EXPECT_EQ(w.lo, 0.0);
  EXPECT_EQ(w.hi, 1.0);
}

TEST(ResultsStatistics, WilsonIntervalRejectsBadArguments) {
  EXPECT_THROW(wilson_interval(11, 10), InvalidParameter);
  EXPECT_THROW(wilson_interval(1, 10, 1.0), InvalidParameter);
  EXPECT_THROW(wilson_interval(1, 10, 0.0), InvalidParameter);
}

TEST(ResultsStatistics, MeanIntervalMatchesRTTest) {
  // t.test(1:5)$conf.int: 1.036757 4.963243; sd(1:5) = sqrt(2.5)
  const std::vector<double> x = {1, 2, 3, 4, 5};
  const MeanInterval m = mean_interval(x);
  EXPECT_EQ(m.n, 5u);
  EXPECT_DOUBLE_EQ(m.mean, 3.0);
  EXPECT_DOUBLE_EQ(m.stddev, std::sqrt(2.5));
  EXPECT_NEAR(m.lo, 1.036757, kRTol);
  EXPECT_NEAR(m.hi, 4.963243, kRTol);
}

TEST(ResultsStatistics, MeanIntervalOfEmptyInputIsFlagged) {
  const MeanInterval m = mean_interval({});
  EXPECT_EQ(m.n, 0u);
  EXPECT_TRUE(std::isnan(m.mean));
  EXPECT_TRUE(std::isnan(m.lo));
  EXPECT_TRUE(std::isnan(m.hi));
  EXPECT_TRUE(std::isnan(m.stddev));
}

TEST(ResultsStatistics, MeanIntervalOfOneValueIsThePoint) {
  const std::vector<double> x = {4.5};
  const MeanInterval m = mean_interval(x);
  EXPECT_EQ(m.n, 1u);
  EXPECT_EQ(m.mean, 4.5);
  EXPECT_EQ(m.lo, 4.5);
  EXPECT_EQ(m.hi, 4.5);
  EXPECT_TRUE(std::isnan(m.stddev));
}

TEST(ResultsStatistics, MeanIntervalOfConstantValuesHasZeroWidth) {
  const std::vector<double> x = {2.0, 2.0, 2.0};
  const MeanInterval m = mean_interval(x);
  EXPECT_EQ(m.stddev, 0.0);
  EXPECT_EQ(m.lo, 2.0);
  EXPECT_EQ(m.hi, 2.0);
}

TEST(ResultsStatistics, MeanIntervalRejectsNonFiniteValues) {
  const std::vector<double> x = {1.0, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW(mean_interval(x), InvalidParameter);
}

TEST(ResultsStatistics, PairedTTestMatchesRSleepExample) {
  // with(sleep, t.test(extra[group == 1], extra[group == 2], paired = TRUE)):
  //   t = -4.0621, df = 9, p-value = 0.002833, mean difference -1.58, 95% CI -2.4598858 -0.7001142
  const PairedTTest t = paired_t_test(kSleep1, kSleep2);
  EXPECT_EQ(t.n, 10u);
  EXPECT_NEAR(t.mean_difference, -1.58, 1e-12);
  EXPECT_NEAR(t.t, -4.0621, 5e-5);
  EXPECT_EQ(t.dof, 9.0);
  EXPECT_NEAR(t.p_two_sided, 0.002833, 5e-7);

  // The same CI is the one-sample interval of the differences.
  std::vector<double> d(kSleep1.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = kSleep1[i] - kSleep2[i];
  const MeanInterval m = mean_interval(d);
  EXPECT_NEAR(m.lo, -2.4598858, kRTol);
  EXPECT_NEAR(m.hi, -0.7001142, kRTol);
}

TEST(ResultsStatistics, PairedTTestIsAntisymmetric) {
  const PairedTTest ab = paired_t_test(kSleep1, kSleep2);
  const PairedTTest ba = paired_t_test(kSleep2, kSleep1);
  EXPECT_DOUBLE_EQ(ba.t, -ab.t);
  EXPECT_DOUBLE_EQ(ba.p_two_sided, ab.p_two_sided);
}

TEST(ResultsStatistics, PairedTTestWithFewerThanTwoPairsIsUndefined) {
  const std::vector<double> a = {1.0};
  const std::vector<double> b = {0.0};
  const PairedTTest t = paired_t_test(a, b);
  EXPECT_EQ(t.n, 1u);
  EXPECT_EQ(t.mean_difference, 1.0);
  EXPECT_TRUE(std::isnan(t.t));
  EXPECT_TRUE(std::isnan(t.p_two_sided));
  EXPECT_TRUE(std::isnan(paired_t_test({}, {}).p_two_sided));
}

TEST(ResultsStatistics, PairedTTestOfIdenticalSamplesHasPOne) {
  const std::vector<double> a = {1.0, 2.0, 3.0};
  const PairedTTest t = paired_t_test(a, a);
  EXPECT_EQ(t.t, 0.0);
  EXPECT_EQ(t.p_two_sided, 1.0);
}

TEST(ResultsStatistics, PairedTTestOfConstantNonZeroDifferenceIsUndefined) {
  const std::vector<double> a = {2.0, 3.0, 4.0};
  const std::vector<double> b = {1.0, 2.0, 3.0};
  const PairedTTest t = paired_t_test(a, b);
  EXPECT_EQ(t.mean_difference, 1.0);
  EXPECT_TRUE(std::isnan(t.t));
  EXPECT_TRUE(std::isnan(t.p_two_sided));
}

TEST(ResultsStatistics, PairedTestsRejectUnequalLengths) {
  const std::vector<double> a = {1.0, 2.0};
  const std::vector<double> b = {1.0};
  EXPECT_THROW(paired_t_test(a, b), InvalidParameter);
  EXPECT_THROW(wilcoxon_signed_rank(a, b), InvalidParameter);
}

TEST(ResultsStatistics, WilcoxonWithTiesAndZeroMatchesRSleepExample) {
  // with(sleep, wilcox.test(extra[group == 1], extra[group == 2], paired = TRUE)): V = 0, p-value = 0.009091
  // (R warns it cannot compute the exact p with ties and zeroes). By hand: the zero is dropped, n = 9, all
  // differences negative so W = 0; |d| ranks 1..9 with the two 1.3 sharing 4.5, tie term 2^3 - 2 = 6;
  // var = 9*10*19/24 - 6/48 = 71.125; z = (0 - 22.5 + 0.5) / sqrt(71.125) = -2.608624;
  // p = 2 * pnorm(-2.608624) = 0.009090698.
  const WilcoxonTest w = wilcoxon_signed_rank(kSleep1, kSleep2);
  EXPECT_EQ(w.n, 9u);
  EXPECT_EQ(w.W, 0.0);
  EXPECT_FALSE(w.exact);
  EXPECT_NEAR(w.z, -2.608624, 1e-6);
  EXPECT_NEAR(w.p_two_sided, 0.009090698, 1e-9);
}

TEST(ResultsStatistics, WilcoxonSmallUntiedSampleIsExactAsInR) {
  // ?wilcox.test: wilcox.test(x, y, paired = TRUE): V = 40, p-value = 0.03906. By hand: the negative
  // differences -0.147 and -0.08 have ranks 3 and 2, so W = 45 - 5 = 40; P(W >= 40) = P(W <= 5) = 10/512
  // (the subsets of 1..9 summing to at most 5: {}, 1, 2, 3, 12, 4, 13, 5, 14, 23), p = 20/512 = 0.0390625.
  const WilcoxonTest w = wilcoxon_signed_rank(kDepressionX, kDepressionY);
  EXPECT_EQ(w.n, 9u);
  EXPECT_EQ(w.W, 40.0);
  EXPECT_TRUE(w.exact);
  EXPECT_DOUBLE_EQ(w.p_two_sided, 20.0 / 512.0);
}

TEST(ResultsStatistics, WilcoxonNormalApproximationWithoutTies) {
  // wilcox.test(x, y, paired = TRUE, exact = FALSE): V = 40, p-value = 0.04401. By hand: var = 71.25,
  // z = (40 - 22.5 - 0.5) / sqrt(71.25) = 2.013986, p = 2 * pnorm(-2.013986) = 0.04401098.
  const WilcoxonTest w = wilcoxon_signed_rank(kDepressionX, kDepressionY, /*allow_exact=*/false);
  EXPECT_FALSE(w.exact);
  EXPECT_NEAR(w.z, 2.013986, 1e-6);
  EXPECT_NEAR(w.p_two_sided, 0.04401098, 1e-8);
}

TEST(ResultsStatistics, WilcoxonIsSymmetricInItsArguments) {
  // Swapping a and b turns W into n(n+1)/2 - W and leaves p unchanged.
  const WilcoxonTest ab = wilcoxon_signed_rank(kDepressionX, kDepressionY);
  const WilcoxonTest ba = wilcoxon_signed_rank(kDepressionY, kDepressionX);
  EXPECT_EQ(ba.W, 45.0 - ab.W);
  EXPECT_DOUBLE_EQ(ba.p_two_sided, ab.p_two_sided);
  EXPECT_DOUBLE_EQ(ba.z, -ab.z);
}

TEST(ResultsStatistics, WilcoxonOfIdenticalSamplesHasPOne) {
  const std::vector<double> a = {1.0, 2.0, 3.0};
  const WilcoxonTest w = wilcoxon_signed_rank(a, a);
  EXPECT_EQ(w.n, 0u);
  EXPECT_EQ(w.W, 0.0);
  EXPECT_TRUE(std::isnan(w.z));
  EXPECT_EQ(w.p_two_sided, 1.0);
}

TEST(ResultsStatistics, WilcoxonExactOnlyBelowFiftyPairs) {
  // 50 distinct positive differences: W is the maximum 1275, and the normal approximation is used (as R).
  std::vector<double> a(50);
  const std::vector<double> b(50, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = static_cast<double>(i + 1);
  const WilcoxonTest w = wilcoxon_signed_rank(a, b);
  EXPECT_EQ(w.W, 1275.0);
  EXPECT_FALSE(w.exact);
  a.pop_back();
  const std::vector<double> b49(49, 0.0);
  const WilcoxonTest exact = wilcoxon_signed_rank(a, b49);
  EXPECT_TRUE(exact.exact);
  EXPECT_DOUBLE_EQ(exact.p_two_sided, 2.0 / std::ldexp(1.0, 49));  // only the all-positive sign pattern
}

}  // namespace
}  // namespace peg3d::results
