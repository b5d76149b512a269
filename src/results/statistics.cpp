#include "results/statistics.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "core/validation.hpp"

namespace peg3d::results {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Below this many non-zero pairs (and without ties) the exact null distribution is used, as in R.
constexpr std::size_t kExactWilcoxonLimit = 50;

void require_confidence(double confidence) { require_in_range("confidence", confidence, 0.0, 1.0, true, true); }

void require_all_finite(std::string_view name, std::span<const double> values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) require_finite(fmt::format("{}[{}]", name, i), values[i]);
  }
}

void require_same_size(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) {
    throw InvalidParameter("b.size()", std::to_string(b.size()),
                           fmt::format("paired samples must have the same length as a ({})", a.size()));
  }
}

std::vector<double> differences(std::span<const double> a, std::span<const double> b) {
  require_same_size(a, b);
  require_all_finite("a", a);
  require_all_finite("b", b);
  std::vector<double> d(a.size());
  std::transform(a.begin(), a.end(), b.begin(), d.begin(), std::minus<>());
  return d;
}

double two_sided_normal_p(double z) {
  const boost::math::normal_distribution<double> normal;
  return std::min(1.0, 2.0 * boost::math::cdf(boost::math::complement(normal, std::abs(z))));
}

// P(W <= w) and P(W >= w) under H0 for the signed-rank statistic of n untied, non-zero differences: each
// rank is positive with probability 1/2, so count the subsets of {1..n} by their sum. Counts are at most
// 2^49 for n < 50, exact in a double.
double exact_signed_rank_two_sided_p(std::size_t n, double w) {
  const std::size_t max_sum = n * (n + 1) / 2;
  std::vector<double> count(max_sum + 1, 0.0);
  count[0] = 1.0;
  for (std::size_t rank = 1; rank <= n; ++rank) {
    for (std::size_t s = rank * (rank + 1) / 2; s >= rank; --s) count[s] += count[s - rank];
  }
  const double total = std::ldexp(1.0, static_cast<int>(n));
  const auto k = static_cast<std::size_t>(std::lround(w));
  // The distribution is symmetric about max_sum / 2: take the tail on W's side, as R does.
  double tail = 0.0;
  if (2 * k > max_sum) {
    for (std::size_t s = k; s <= max_sum; ++s) tail += count[s];
  } else {
    for (std::size_t s = 0; s <= k; ++s) tail += count[s];
  }
  return std::min(1.0, 2.0 * tail / total);
}

}  // namespace

double normal_critical_value(double confidence) {
  require_confidence(confidence);
  const boost::math::normal_distribution<double> normal;
  return boost::math::quantile(boost::math::complement(normal, (1.0 - confidence) / 2.0));
}

double t_critical_value(double confidence, double dof) {
  require_confidence(confidence);
  require_positive("dof", dof);
  const boost::math::students_t_distribution<double> t(dof);
  return boost::math::quantile(boost::math::complement(t, (1.0 - confidence) / 2.0));
}

ProportionInterval wilson_interval(std::size_t successes, std::size_t trials, double confidence) {
  require_confidence(confidence);
  if (successes > trials) {
    throw InvalidParameter("successes", std::to_string(successes), fmt::format("must be <= trials ({})", trials));
  }
  if (trials == 0) return {kNaN, 0.0, 1.0};

  const double z = normal_critical_value(confidence);
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z2n = z * z / n;
  const double center = (p + z2n / 2.0) / (1.0 + z2n);
  const double half = z / (1.0 + z2n) * std::sqrt(p * (1.0 - p) / n + z2n / (4.0 * n));
  // 0/n and n/n touch the bound analytically; the clamp only removes rounding (e.g. 1e-17 instead of 0).
  const double lo = successes == 0 ? 0.0 : std::clamp(center - half, 0.0, p);
  const double hi = successes == trials ? 1.0 : std::clamp(center + half, p, 1.0);
  return {p, lo, hi};
}

MeanInterval mean_interval(std::span<const double> values, double confidence) {
  require_confidence(confidence);
  require_all_finite("values", values);
  const std::size_t n = values.size();
  if (n == 0) return {kNaN, kNaN, kNaN, kNaN, 0};

  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(n);
  if (n == 1) return {mean, mean, mean, kNaN, 1};

  // Two-pass variance: the sum of squared deviations, not E[x^2] - E[x]^2, which cancels badly.
  double ss = 0.0;
  for (double v : values) ss += (v - mean) * (v - mean);
  const double stddev = std::sqrt(ss / static_cast<double>(n - 1));
  const double dof = static_cast<double>(n - 1);
  const double half = t_critical_value(confidence, dof) * stddev / std::sqrt(static_cast<double>(n));
  return {mean, mean - half, mean + half, stddev, n};
}

PairedTTest paired_t_test(std::span<const double> a, std::span<const double> b) {
  const std::vector<double> d = differences(a, b);
  const std::size_t n = d.size();
  PairedTTest result;
  result.n = n;
  if (n == 0) {
    result.mean_difference = result.t = result.p_two_sided = kNaN;
    return result;
  }
  const MeanInterval m = mean_interval(d);
  result.mean_difference = m.mean;
  result.dof = static_cast<double>(n - 1);
  if (n < 2) {
    result.t = result.p_two_sided = kNaN;
    return result;
  }
  if (m.stddev == 0.0) {
    const bool identical = std::all_of(d.begin(), d.end(), [](double x) { return x == 0.0; });
    result.t = identical ? 0.0 : kNaN;
    result.p_two_sided = identical ? 1.0 : kNaN;
    return result;
  }
  result.t = m.mean / (m.stddev / std::sqrt(static_cast<double>(n)));
  const boost::math::students_t_distribution<double> t(result.dof);
  result.p_two_sided = std::min(1.0, 2.0 * boost::math::cdf(boost::math::complement(t, std::abs(result.t))));
  return result;
}

WilcoxonTest wilcoxon_signed_rank(std::span<const double> a, std::span<const double> b, bool allow_exact) {
  std::vector<double> d = differences(a, b);
  const std::size_t pairs = d.size();
  std::erase(d, 0.0);
  const bool had_zeros = d.size() != pairs;
  const std::size_t n = d.size();

  WilcoxonTest result;
  result.n = n;
  if (n == 0) {
    result.z = kNaN;
    return result;  // W = 0, p = 1
  }

  // Rank |d| ascending; a run of equal |d| shares the average of the ranks it spans.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return std::abs(d[i]) < std::abs(d[j]); });
  double w_plus = 0.0;
  double tie_term = 0.0;  // sum over tie groups of t^3 - t
  for (std::size_t first = 0; first < n;) {
    std::size_t last = first + 1;
    while (last < n && std::abs(d[order[last]]) == std::abs(d[order[first]])) ++last;
    const double size = static_cast<double>(last - first);
    const double rank = static_cast<double>(first + last + 1) / 2.0;  // mean of ranks first+1 .. last
    for (std::size_t k = first; k < last; ++k) {
      if (d[order[k]] > 0.0) w_plus += rank;
    }
    tie_term += size * size * size - size;
    first = last;
  }
  result.W = w_plus;

  const double nd = static_cast<double>(n);
  const double mean = nd * (nd + 1.0) / 4.0;
  const double variance = nd * (nd + 1.0) * (2.0 * nd + 1.0) / 24.0 - tie_term / 48.0;
  const double centered = w_plus - mean;
  const double correction = centered > 0.0 ? 0.5 : (centered < 0.0 ? -0.5 : 0.0);
  result.z = (centered - correction) / std::sqrt(variance);

  result.exact = allow_exact && n < kExactWilcoxonLimit && tie_term == 0.0 && !had_zeros;
  result.p_two_sided = result.exact ? exact_signed_rank_two_sided_p(n, w_plus) : two_sided_normal_p(result.z);
  return result;
}

}  // namespace peg3d::results
