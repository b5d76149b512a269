#pragma once
// A static index over axis-aligned boxes: which boxes overlap a query box, and the boxes in order of their
// distance to a point within a bound (branch and bound). It answers the broadphase questions of the movers'
// timeline (world/bodies/mover_timeline.hpp): built once per time window, read by every thread.
//
// The same n boxes may come in several frames (a mover's bounds over each block of a window): each frame has
// bounds of its own, the clusters are shared and bound the boxes of every frame. A query asks one frame. The
// queries of the window's next frames then find the cluster level (and the memory it lives in) where the first
// one left it.
//
// Three flat levels instead of a deep tree: the boxes in clusters of at most 16 that lie near each other (the
// cells of median splits along the widest spread), the clusters' bounds, and the bounds of groups of eight
// neighbouring clusters (the cells a few splits up), so that a query near nothing is over at the top. Each
// level's bounds lie side by side, one coordinate of every box in a row, so a query measures four boxes with
// one instruction each (SSE2,
// or plain loops elsewhere: the same floats) in straight-line code that reads memory in order: no chain of
// dependent loads from node to node, which costs a cache miss a level when a window's index is cold. Bounds are
// relative to the boxes' lowest corner, rounded outwards: floats for groups and clusters, and for the boxes
// themselves (most of the memory) 16-bit steps of a 65000th of the extent, half the bytes a query reads. Every
// query widens its bound by a slack far above float rounding, so no box it should report is missed (it may
// report one that misses by a few steps, which callers test exactly anyway). What a query reports does not depend on the clustering: callers that
// need an exact answer break ties by box index themselves.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/vector.hpp"

namespace peg3d {

class BoxIndex {
 public:
  /// Most boxes an index holds (the buffers of a query live on the stack).
  static constexpr std::size_t kMaxBoxes = 8192;

  BoxIndex() = default;
  /// Boxes 0..n-1 in each of `frames` frames (each with lo <= hi): box i of frame f is boxes[f n + i], n <=
  /// kMaxBoxes.
  explicit BoxIndex(std::span<const Box> boxes, int frames = 1);

  /// Boxes a frame.
  std::size_t size() const { return size_; }
  int frames() const { return frames_; }
  /// Bytes the index holds.
  std::size_t bytes() const {
    return floats_.capacity() * sizeof(float) + steps_.capacity() * sizeof(std::uint16_t) + ints_.capacity() * sizeof(std::int32_t);
  }

  /// Calls visit(box) for every box of `frame` that meets `query` (closed boxes: touching counts), in no
  /// particular order. No allocation.
  template <class Visit>
  void overlapping(int frame, const Box& query, Visit&& visit) const;
  template <class Visit>
  void overlapping(const Box& query, Visit&& visit) const { overlapping(0, query, visit); }

  /// Visits the boxes of `frame` that lie within `bound` of p (the distance from p to the box, 0 inside), nearer
  /// ones first: visit(box) returns the new bound (the best distance found so far, or `bound` unchanged), and
  /// boxes farther than the bound are skipped. No allocation.
  template <class Visit>
  void nearest(int frame, const Vec3& p, double bound, Visit&& visit) const;
  template <class Visit>
  void nearest(const Vec3& p, double bound, Visit&& visit) const { nearest(0, p, bound, visit); }

  /// Visits the boxes of `frame` that the ray from `origin` along the unit `direction` enters within `bound`
  /// (entry 0 when it starts inside), earlier entries first: visit(box) returns the new bound (the nearest hit
  /// found so far, or `bound` unchanged), and boxes entered beyond it are skipped. No allocation.
  template <class Visit>
  void along(int frame, const Vec3& origin, const Vec3& direction, double bound, Visit&& visit) const;

 private:
  static constexpr int kClusterSize = 16;
  static constexpr int kGroupSize = 8;  ///< clusters a group
  static constexpr int kMaxClusters = int(kMaxBoxes / (kClusterSize / 2)) + kGroupSize;
  static constexpr int kMaxGroups = kMaxClusters / kGroupSize + 4;

  /// One level's bounds, side by side: lo[axis][i], hi[axis][i], padded to a multiple of four with boxes that
  /// contain nothing. Groups and clusters in floats (m from the origin); boxes, the bulk of the memory a query
  /// reads, in 16-bit steps of unit_ from the origin (lo rounded down, hi up).
  template <class T>
  struct Level {
    const T* lo[3];
    const T* hi[3];
  };
  template <class T>
  static Level<T> level(const T* f, int count) {
    return {{f, f + count, f + 2 * count}, {f + 3 * count, f + 4 * count, f + 5 * count}};
  }
  Level<float> groups() const { return level(floats_.data(), group_count_); }
  Level<float> clusters() const { return level(floats_.data() + 6 * std::size_t(group_count_), cluster_count_); }
  Level<std::uint16_t> boxes(int frame) const {
    return level(steps_.data() + 6 * std::size_t(frame) * std::size_t(slot_count_), slot_count_);
  }
  const std::int32_t* first() const { return ints_.data(); }                       // per cluster, its first slot
  const std::int32_t* count() const { return ints_.data() + cluster_count_; }      // per cluster, its slots (x 4)
  const std::int32_t* id() const { return ints_.data() + 2 * cluster_count_; }     // per slot, its box or -1

  /// Squared distances (float) from q to the boxes [begin, begin + n) of a level, n a multiple of four, in
  /// d2[0, n); appends to `out` the k whose d2[k] <= limit and returns how many.
  /// q, d2 and limit are in the level's units (m for floats, unit_ for steps).
  template <class T>
  static int within(const Level<T>& level, int begin, int n, const float q[3], float limit, float* d2, std::int32_t* out);
  /// Where a ray (origin o relative to the index's origin, direction d, both in m) enters each of the boxes
  /// [begin, begin + n) of a level, widened by `widen` (m): in t[0, n) the entry (0 inside), +inf for a box it
  /// misses; appends to `out` the k entered within `limit` and returns how many. `scale` turns the level's units
  /// into m.
  template <class T>
  static int entered(const Level<T>& level, int begin, int n, const float o[3], const float d[3], float scale,
                     float widen, float limit, float* t, std::int32_t* out);
  /// Whether each of the boxes [begin, begin + n) of a level meets [lo, hi] (1 or 0 in `out`).
  template <class T>
  static void overlaps(const Level<T>& level, int begin, int n, const float lo[3], const float hi[3], std::int32_t* out);

  /// The query's slack (m): float rounding of coordinates as far as `reach` from the origin is far below it.
  double slack(double reach) const { return 1e-6 * (1.0 + extent_ + reach); }
  /// The point relative to the origin, in floats.
  void relative(const Vec3& p, float out[3]) const {
    for (int a = 0; a < 3; ++a) out[a] = static_cast<float>(p[a] - origin_[a]);
  }
  /// The squared bound a box's float distance is held against: the bound widened by the slack.
  float limit2(double bound, double reach) const {
    const double b = bound + slack(reach);
    return static_cast<float>(b * b * (1.0 + 1e-6));
  }

  std::vector<float> floats_;        // the groups' level, then the clusters' level
  std::vector<std::uint16_t> steps_; // each frame's boxes' level
  double unit_ = 1.0;                // m, a step of steps_
  std::vector<std::int32_t> ints_;   // per cluster its first slot, per cluster its slot count, per slot its box
  int group_count_ = 0;              // padded to a multiple of four
  int cluster_count_ = 0;            // kGroupSize a group: padded to a multiple of it
  int slot_count_ = 0;               // every cluster's boxes, each cluster padded to a multiple of four
  std::array<double, 3> origin_{};
  double extent_ = 0.0;              // m, the largest coordinate relative to the origin
  std::size_t size_ = 0;
  int frames_ = 1;
};

template <class Visit>
void BoxIndex::overlapping(int frame, const Box& query, Visit&& visit) const {
  if (size_ == 0) return;
  float lo[3], hi[3];
  const double s = slack((query.hi - query.lo).cwiseAbs().maxCoeff() + (query.lo - Vec3(origin_.data())).cwiseAbs().maxCoeff());
  for (int a = 0; a < 3; ++a) {
    lo[a] = static_cast<float>(query.lo[a] - origin_[a] - s);
    hi[a] = static_cast<float>(query.hi[a] - origin_[a] + s);
  }
  const Level<float> gr = groups(), cl = clusters();
  const Level<std::uint16_t> bx = boxes(frame);
  float lo_steps[3], hi_steps[3];
  for (int a = 0; a < 3; ++a) {
    lo_steps[a] = static_cast<float>((query.lo[a] - origin_[std::size_t(a)] - s) / unit_);
    hi_steps[a] = static_cast<float>((query.hi[a] - origin_[std::size_t(a)] + s) / unit_);
  }
  const std::int32_t *firsts = first(), *counts = count(), *ids = id();
  alignas(16) std::int32_t group_hit[kMaxGroups], hit[kGroupSize], in[kClusterSize];
  overlaps(gr, 0, group_count_, lo, hi, group_hit);
  for (int g = 0; g < group_count_; ++g) {
    if (!group_hit[g]) continue;
    overlaps(cl, g * kGroupSize, kGroupSize, lo, hi, hit);
    for (int j = 0; j < kGroupSize; ++j) {
      if (!hit[j]) continue;
      const int c = g * kGroupSize + j, from = firsts[c], n = counts[c];
      overlaps(bx, from, n, lo_steps, hi_steps, in);
      for (int k = 0; k < n; ++k) {
        if (in[k] && ids[from + k] >= 0) visit(int(ids[from + k]));
      }
    }
  }
}

template <class Visit>
void BoxIndex::nearest(int frame, const Vec3& p, double bound, Visit&& visit) const {
  if (size_ == 0 || !(bound >= 0.0)) return;
  float q[3];
  relative(p, q);
  const double reach = (p - Vec3(origin_.data())).cwiseAbs().maxCoeff();
  float limit = limit2(bound, reach);
  // The boxes' level in steps: the point and the bound in them too.
  const float to_steps = static_cast<float>(1.0 / unit_), to_steps2 = to_steps * to_steps;
  const float q_steps[3] = {q[0] * to_steps, q[1] * to_steps, q[2] * to_steps};
  float limit_steps = limit * to_steps2 * (1.0f + 1e-6f);
  const Level<std::uint16_t> bx = boxes(frame);
  const std::int32_t *firsts = first(), *counts = count(), *ids = id();
  // The clusters within the bound, taken nearest first: by then the bound has pruned most of them, so each
  // round picks the nearest pending one and drops those beyond the bound instead of sorting them all. Branch
  // free where the outcome is a coin toss (is this box within the bound?).
  alignas(16) float gd2[kMaxGroups], cd2[kMaxClusters];
  std::int32_t near_groups[kMaxGroups], pending[kMaxClusters];
  const int g = within(groups(), 0, group_count_, q, limit, gd2, near_groups);
  int m = 0;
  const Level<float> cl = clusters();
  for (int j = 0; j < g; ++j) {
    const int first_cluster = near_groups[j] * kGroupSize;
    std::int32_t in[kGroupSize];
    const int k = within(cl, first_cluster, kGroupSize, q, limit, cd2 + first_cluster, in);
    for (int i = 0; i < k; ++i) pending[m++] = first_cluster + in[i];
  }
  alignas(16) float bd2[kClusterSize];
  while (m > 0) {
    int at = 0, kept = 0;
    for (int j = 0; j < m; ++j) {
      const std::int32_t c = pending[j];
      const bool within = cd2[c] <= limit;
      pending[kept] = c;
      at = within && cd2[c] < cd2[pending[at]] ? kept : at;
      kept += within;
    }
    m = kept;
    if (m == 0) break;
    const int c = pending[at];
    pending[at] = pending[--m];
    const int from = firsts[c];
    // Its boxes within the bound, nearest first, likewise: the first visits tighten the bound.
    std::int32_t near[kClusterSize];
    int h = within(bx, from, counts[c], q_steps, limit_steps, bd2, near);
    while (h > 0) {
      int best = 0;
      for (int i = 1; i < h; ++i) best = bd2[near[i]] < bd2[near[best]] ? i : best;
      const int k = near[best];
      if (!(bd2[k] <= limit_steps)) break;
      near[best] = near[--h];
      if (ids[from + k] < 0) continue;  // a padding slot (only an infinite bound reaches one)
      bound = visit(int(ids[from + k]));
      limit = limit2(bound, reach);
      limit_steps = limit * to_steps2 * (1.0f + 1e-6f);
    }
  }
}

template <class Visit>
void BoxIndex::along(int frame, const Vec3& origin, const Vec3& direction, double bound, Visit&& visit) const {
  if (size_ == 0 || !(bound >= 0.0)) return;
  float o[3];
  relative(origin, o);
  const float d[3] = {static_cast<float>(direction.x()), static_cast<float>(direction.y()), static_cast<float>(direction.z())};
  // Rounding the origin, the direction and the boxes to floats moves them by far less than the slack at the
  // farthest point the ray reaches.
  const double reach = (origin - Vec3(origin_.data())).cwiseAbs().maxCoeff() + (std::isfinite(bound) ? bound : extent_);
  const float widen = static_cast<float>(slack(reach));
  float limit = static_cast<float>(bound) + widen;
  const float unit = static_cast<float>(unit_);
  const Level<std::uint16_t> bx = boxes(frame);
  const std::int32_t *firsts = first(), *counts = count(), *ids = id();
  alignas(16) float gt[kMaxGroups], ct[kMaxClusters];
  std::int32_t entered_groups[kMaxGroups], pending[kMaxClusters];
  const int g = entered(groups(), 0, group_count_, o, d, 1.0f, widen, limit, gt, entered_groups);
  int m = 0;
  const Level<float> cl = clusters();
  for (int j = 0; j < g; ++j) {
    const int first_cluster = entered_groups[j] * kGroupSize;
    std::int32_t in[kGroupSize];
    const int k = entered(cl, first_cluster, kGroupSize, o, d, 1.0f, widen, limit, ct + first_cluster, in);
    for (int i = 0; i < k; ++i) pending[m++] = first_cluster + in[i];
  }
  // As nearest(): the pending cluster entered first, then its boxes entered first, each visit tightening the
  // bound.
  alignas(16) float bt[kClusterSize];
  while (m > 0) {
    int at = 0, kept = 0;
    for (int j = 0; j < m; ++j) {
      const std::int32_t c = pending[j];
      const bool within = ct[c] <= limit;
      pending[kept] = c;
      at = within && ct[c] < ct[pending[at]] ? kept : at;
      kept += within;
    }
    m = kept;
    if (m == 0) break;
    const int c = pending[at];
    pending[at] = pending[--m];
    const int from = firsts[c];
    std::int32_t near[kClusterSize];
    int h = entered(bx, from, counts[c], o, d, unit, widen, limit, bt, near);
    while (h > 0) {
      int best = 0;
      for (int i = 1; i < h; ++i) best = bt[near[i]] < bt[near[best]] ? i : best;
      const int k = near[best];
      if (!(bt[k] <= limit)) break;
      near[best] = near[--h];
      if (ids[from + k] < 0) continue;
      bound = visit(int(ids[from + k]));
      limit = static_cast<float>(bound) + widen;
    }
  }
}

}  // namespace peg3d
