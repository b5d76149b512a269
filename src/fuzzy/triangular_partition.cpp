#include "fuzzy/triangular_partition.hpp"

#include <cmath>

#include "core/validation.hpp"

namespace peg3d::fuzzy {

TriangularPartition::TriangularPartition(double lo, double hi, int sets, const char* name) : lo_(lo), hi_(hi), sets_(sets) {
  require_range(name, lo, hi);
  require_at_least(std::string(name) + ".sets", sets, 2);
  width_ = (hi - lo) / (sets - 1);
  inv_width_ = 1.0 / width_;
}

double TriangularPartition::membership(int k, double x) const {
  assert(k >= 0 && k < sets_);
  const double xc = std::clamp(x, lo_, hi_);
  return std::max(0.0, 1.0 - std::abs(xc - center(k)) * inv_width_);
}

}  // namespace peg3d::fuzzy
