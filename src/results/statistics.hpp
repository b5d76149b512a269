#pragma once
// The summary numbers and tests a reviewer expects next to an experiment's results: confidence intervals for
// a success rate and for a mean, and two paired tests for "is algorithm A better than B on the same seeds".
// Every function is pure. Degenerate inputs (no data, zero variance) never divide by zero: each result
// documents what it returns then. Non-finite inputs are rejected with InvalidParameter (filter NaN metrics,
// e.g. the capture time of an episode without capture, before calling).

#include <cstddef>
#include <span>

namespace peg3d::results {

/// Two-sided confidence interval of a binomial proportion.
struct ProportionInterval {
  double rate = 0.0;  ///< successes / trials, in [0, 1]; NaN when trials == 0
  double lo = 0.0;    ///< lower bound, in [0, rate]; 0 when trials == 0
  double hi = 1.0;    ///< upper bound, in [rate, 1]; 1 when trials == 0
};

/// Wilson score interval (Wilson 1927), the interval R's prop.test(x, n, correct = FALSE) reports. Unlike the
/// Wald interval it stays inside [0, 1] and does not collapse to a point at 0/n or n/n.
/// trials == 0 carries no information: rate is NaN and the interval is all of [0, 1].
/// confidence in (0, 1); successes <= trials. Throws InvalidParameter otherwise.
ProportionInterval wilson_interval(std::size_t successes, std::size_t trials, double confidence = 0.95);

/// Sample mean with its two-sided Student-t confidence interval.
struct MeanInterval {
  double mean = 0.0;    ///< sample mean; NaN when n == 0
  double lo = 0.0;      ///< lower bound mean - t * stddev / sqrt(n); NaN when n == 0, mean when n == 1
  double hi = 0.0;      ///< upper bound; NaN when n == 0, mean when n == 1
  double stddev = 0.0;  ///< sample standard deviation (divisor n - 1), >= 0; NaN when n < 2
  std::size_t n = 0;    ///< number of values; 0 flags the empty result (all other fields NaN)
};

/// Mean and its t interval (R: t.test(x)$conf.int). With a single value there is no spread to estimate: the
/// interval is reported as the point [mean, mean] and stddev as NaN; consumers that need a real interval
/// must check n >= 2. Zero spread gives lo == hi == mean. confidence in (0, 1).
MeanInterval mean_interval(std::span<const double> values, double confidence = 0.95);

/// Paired Student t test of mean(a - b) == 0 (R: t.test(a, b, paired = TRUE)).
struct PairedTTest {
  double mean_difference = 0.0;  ///< mean of a[i] - b[i]; NaN when n == 0
  double t = 0.0;                ///< t statistic mean / (sd / sqrt(n)); NaN when undefined (see below)
  double dof = 0.0;              ///< degrees of freedom n - 1; 0 when n == 0
  double p_two_sided = 1.0;      ///< two-sided p value in [0, 1]; NaN when undefined (see below)
  std::size_t n = 0;             ///< number of pairs
};

/// Paired t test. a and b must have the same length (InvalidParameter otherwise).
/// Degenerate cases, where the statistic would be 0/0 or x/0:
///  - n < 2: no variance estimate; t and p are NaN.
///  - every difference is exactly 0 (the samples are identical pair by pair): t = 0 and p = 1.
///  - the differences are all equal but not 0: the test is undefined (R refuses: "data are essentially
///    constant"); t and p are NaN rather than a claim of infinite significance.
PairedTTest paired_t_test(std::span<const double> a, std::span<const double> b);

/// Wilcoxon signed-rank test of a - b being symmetric about 0 (R: wilcox.test(a, b, paired = TRUE)).
struct WilcoxonTest {
  double W = 0.0;            ///< sum of the ranks of the positive differences a - b (R's V), in [0, n(n+1)/2]
  double z = 0.0;            ///< normal-approximation statistic with continuity correction; NaN when n == 0
  double p_two_sided = 1.0;  ///< two-sided p value in [0, 1]
  std::size_t n = 0;         ///< pairs with a non-zero difference (zero differences are dropped)
  bool exact = false;        ///< true when p comes from the exact null distribution rather than from z
};

/// Wilcoxon signed-rank test. Zero differences are dropped; tied |differences| (equal as doubles, as in R:
/// round metrics first if 0.1 + 0.2 and 0.3 should tie) get their average rank, and the variance is
/// tie-corrected: n(n+1)(2n+1)/24 - sum(t^3 - t)/48 over the tie groups. z is
/// (W - n(n+1)/4 - sign(W - n(n+1)/4) * 0.5) / sqrt(variance): R's continuity correction.
/// p: exact (enumerated null distribution of W, as R) when allow_exact, n < 50 and there were no ties and
/// no zero differences; otherwise 2 * (1 - Phi(|z|)), as R with exact = FALSE or with ties.
/// n == 0 after dropping zeros (a == b pair by pair): W = 0, z = NaN, p = 1 (nothing suggests a difference).
/// a and b must have the same length (InvalidParameter otherwise).
WilcoxonTest wilcoxon_signed_rank(std::span<const double> a, std::span<const double> b, bool allow_exact = true);

/// Two-sided standard normal quantile for a confidence level: Phi^-1(1 - (1 - confidence) / 2), e.g. 1.96
/// for 0.95. confidence in (0, 1).
double normal_critical_value(double confidence);

/// Two-sided Student t quantile with dof degrees of freedom (> 0), e.g. 2.262 for 0.95 and 9 dof.
double t_critical_value(double confidence, double dof);

}  // namespace peg3d::results
