#pragma once
// A zero-order Takagi-Sugeno rule base over n inputs (paper eq. 7-9): one rule per combination of fuzzy
// sets, firing strength = product of memberships (product t-norm), normalised over all rules. With strong
// triangular partitions only the 2^n rules around the input fire, so evaluation visits those and never
// the whole table (16 of 625 rules for the paper's 4 inputs x 5 sets).

#include <array>
#include <span>
#include <vector>

#include "fuzzy/triangular_partition.hpp"

namespace peg3d::fuzzy {

inline constexpr int kMaxInputs = 8;
inline constexpr int kMaxFiredRules = 1 << kMaxInputs;

/// The rules that fire for one input vector, with normalised strengths Phi_l (summing to 1).
/// Fixed capacity, so firing never allocates.
struct FiredRules {
  int count = 0;
  std::array<int, kMaxFiredRules> rule{};
  std::array<double, kMaxFiredRules> strength{};
};

class RuleBase {
 public:
  /// 1 <= inputs <= kMaxInputs. Throws InvalidParameter otherwise.
  explicit RuleBase(std::vector<TriangularPartition> partitions);

  int inputs() const { return static_cast<int>(inputs_.size()); }
  /// L = product of the set counts.
  int rules() const { return rules_; }
  const TriangularPartition& input(int i) const { return inputs_[i]; }

  /// Rule index of a combination of sets (one per input); input 0 is the most significant digit.
  int rule_index(std::span<const int> sets) const;

  /// Sparse firing: the 2^n rules around x with their normalised strengths. x.size() == inputs().
  void fire(std::span<const double> x, FiredRules& out) const;

  /// Dense reference (eq. 9 literally): phi[l] for every rule l. phi.size() == rules().
  void fire_dense(std::span<const double> x, std::span<double> phi) const;

 private:
  std::vector<TriangularPartition> inputs_;
  std::vector<int> stride_;
  int rules_ = 1;
};

/// Output j of a zero-order TS system whose consequents are stored rule-major, table[l * outputs + j]:
/// y_j = sum_l Phi_l table[l * outputs + j].
inline double ts_output(const FiredRules& fired, std::span<const double> table, int outputs, int j) {
  double y = 0.0;
  for (int i = 0; i < fired.count; ++i) y += fired.strength[i] * table[fired.rule[i] * outputs + j];
  return y;
}

/// Dense counterpart of ts_output over all rules.
inline double ts_output_dense(std::span<const double> phi, std::span<const double> table, int outputs, int j) {
  double y = 0.0;
  for (std::size_t l = 0; l < phi.size(); ++l) y += phi[l] * table[l * outputs + j];
  return y;
}

}  // namespace peg3d::fuzzy
