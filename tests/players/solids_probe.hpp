#pragma once
// A SightProbe over axis-aligned boxes, answered exactly: the players' tests build walls, holes and closed rooms
// from boxes and know every segment's and point's answer.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "game/policy.hpp"

namespace peg3d::testing {

struct BoxesProbe final : game::SightProbe {
  std::vector<Box> solids;
  // Whether the segment a-b meets the closed box (slab test).
  static bool meets(const Box& s, const Vec3& a, const Vec3& b) {
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double d = b[k] - a[k];
      if (d == 0.0) {
        if (a[k] < s.lo[k] || a[k] > s.hi[k]) return false;
        continue;
      }
      double u = (s.lo[k] - a[k]) / d, v = (s.hi[k] - a[k]) / d;
      if (u > v) std::swap(u, v);
      t0 = std::max(t0, u), t1 = std::min(t1, v);
      if (t0 > t1) return false;
    }
    return true;
  }
  bool clear(const Vec3& a, const Vec3& b) const override {
    return std::none_of(solids.begin(), solids.end(), [&](const Box& s) { return meets(s, a, b); });
  }
  double clearance(const Vec3& p) const override {
    double d = std::numeric_limits<double>::infinity();
    for (const Box& s : solids) d = std::min(d, (p - s.clamp(p)).norm());
    return d;
  }
};

/// A wall 1 m thick across the 20 x 20 x 8 m arena at x = 9.5-10.5 m, full height, with one opening of width `w`
/// centred at y = `hole` (the only way from one side to the other).
inline BoxesProbe wall_with_hole(double hole, double w) {
  BoxesProbe p;
  p.solids = {Box{{9.5, -1, -1}, {10.5, hole - 0.5 * w, 9}}, Box{{9.5, hole + 0.5 * w, -1}, {10.5, 21, 9}}};
  return p;
}

}  // namespace peg3d::testing
