#include "fuzzy/rule_base.hpp"

#include <cassert>

#include "core/validation.hpp"

namespace peg3d::fuzzy {

RuleBase::RuleBase(std::vector<TriangularPartition> partitions) : inputs_(std::move(partitions)) {
  require_at_least("rule_base.inputs", static_cast<long long>(inputs_.size()), 1);
  if (inputs_.size() > static_cast<std::size_t>(kMaxInputs)) {
    throw InvalidParameter("rule_base.inputs", std::to_string(inputs_.size()), "must be <= 8");
  }
  stride_.assign(inputs_.size(), 1);
  long long rules = 1;
  for (int i = inputs() - 1; i >= 0; --i) {
    stride_[i] = static_cast<int>(rules);
    rules *= inputs_[i].sets();
    if (rules > (1 << 24)) throw InvalidParameter("rule_base.rules", std::to_string(rules), "must be <= 2^24");
  }
  rules_ = static_cast<int>(rules);
}

int RuleBase::rule_index(std::span<const int> sets) const {
  assert(static_cast<int>(sets.size()) == inputs());
  int l = 0;
  for (int i = 0; i < inputs(); ++i) l += sets[i] * stride_[i];
  return l;
}

namespace {

// RuleBase::fire for a rule base of N inputs known at compile time, so that the 2^N products and the sum
// unroll: entry e takes the upper set of input i when bit i of e is set. Each strength is the product over
// the inputs in input order and the sum runs in entry order, as in the general loop below: the same bits.
template <int N>
void fire_fixed(const Activation* a, const int* stride, FiredRules& out) {
  constexpr int kCount = 1 << N;
  double lower[N], upper[N];
  int base = 0;
  for (int i = 0; i < N; ++i) {
    lower[i] = 1.0 - a[i].t;
    upper[i] = a[i].t;
    base += a[i].lower * stride[i];
  }
  out.count = kCount;
  double sum = 0.0;
  for (int e = 0; e < kCount; ++e) {
    double w = 1.0;
    int r = base;
    for (int i = 0; i < N; ++i) {
      const bool up = (e >> i) & 1;
      w *= up ? upper[i] : lower[i];
      r += up ? stride[i] : 0;
    }
    out.rule[e] = r;
    out.strength[e] = w;
    sum += w;
  }
  const double inv = 1.0 / sum;
  for (int e = 0; e < kCount; ++e) out.strength[e] *= inv;
}

}  // namespace

void RuleBase::fire(std::span<const double> x, FiredRules& out) const {
  assert(static_cast<int>(x.size()) == inputs());
  if (inputs() == 4 || inputs() == 6) {  // the game's channels: four inputs per angle, or six for both
    Activation a[6];
    for (int i = 0; i < inputs(); ++i) a[i] = inputs_[i].activate(x[i]);
    if (inputs() == 4) {
      fire_fixed<4>(a, stride_.data(), out);
    } else {
      fire_fixed<6>(a, stride_.data(), out);
    }
    return;
  }
  // Grow the list input by input: each entry splits into (lower set, 1 - t) and (upper set, t).
  out.count = 1;
  out.rule[0] = 0;
  out.strength[0] = 1.0;
  for (int i = 0; i < inputs(); ++i) {
    const Activation a = inputs_[i].activate(x[i]);
    const int base = a.lower * stride_[i];
    const int n = out.count;
    for (int e = 0; e < n; ++e) {
      const int r = out.rule[e] + base;
      const double w = out.strength[e];
      out.rule[e] = r;
      out.strength[e] = w * (1.0 - a.t);
      out.rule[n + e] = r + stride_[i];
      out.strength[n + e] = w * a.t;
    }
    out.count = 2 * n;
  }
  // Eq. (9): normalise. A strong partition already sums to 1 up to rounding; dividing keeps it exact.
  double sum = 0.0;
  for (int e = 0; e < out.count; ++e) sum += out.strength[e];
  const double inv = 1.0 / sum;
  for (int e = 0; e < out.count; ++e) out.strength[e] *= inv;
}

void RuleBase::fire_dense(std::span<const double> x, std::span<double> phi) const {
  assert(static_cast<int>(x.size()) == inputs() && static_cast<int>(phi.size()) == rules_);
  double sum = 0.0;
  for (int l = 0; l < rules_; ++l) {
    double w = 1.0;
    int rest = l;
    for (int i = 0; i < inputs(); ++i) {
      const int k = rest / stride_[i];
      rest -= k * stride_[i];
      w *= inputs_[i].membership(k, x[i]);
    }
    phi[l] = w;
    sum += w;
  }
  for (double& p : phi) p /= sum;
}

}  // namespace peg3d::fuzzy
