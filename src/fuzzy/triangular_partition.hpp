#pragma once
// A partition of an input range into N evenly spaced triangular fuzzy sets (a "strong" partition): set k
// peaks at c_k = lo + k h, h = (hi - lo) / (N - 1), and falls to 0 at c_{k-1} and c_{k+1}. Inside [lo, hi]
// at most two neighbouring sets are non-zero and the memberships sum to 1; inputs outside are clamped.

#include <algorithm>
#include <cassert>

namespace peg3d::fuzzy {

/// The (at most) two sets an input activates: set `lower` with weight 1 - t, set lower + 1 with weight t.
struct Activation {
  int lower = 0;    ///< index of the lower set, in [0, N-2]
  double t = 0.0;   ///< weight of set lower + 1, in [0, 1]
};

class TriangularPartition {
 public:
  /// lo < hi (finite), sets >= 2. Throws InvalidParameter naming `name` (e.g. "pursuer.inputs[1]").
  TriangularPartition(double lo, double hi, int sets, const char* name = "partition");

  double lo() const { return lo_; }
  double hi() const { return hi_; }
  int sets() const { return sets_; }
  /// Peak of set k.
  double center(int k) const { return lo_ + k * width_; }

  /// The activated pair for x (clamped to [lo, hi]). Cheap: one division-free multiply and a floor.
  Activation activate(double x) const {
    // Clamping u as well as x keeps rounding from pushing t past 1 at the top end.
    const double u = std::min((std::clamp(x, lo_, hi_) - lo_) * inv_width_, sets_ - 1.0);  // in [0, sets-1]
    const int k = std::min(static_cast<int>(u), sets_ - 2);  // x == hi activates the last set fully
    assert(k >= 0);
    return {k, u - k};
  }

  /// Membership of set k at x (clamped): the dense definition, for reference and plots.
  double membership(int k, double x) const;

 private:
  double lo_, hi_;
  int sets_;
  double width_, inv_width_;
};

}  // namespace peg3d::fuzzy
