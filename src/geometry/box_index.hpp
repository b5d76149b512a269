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
// one instruction each (SSE2, a fan's rays eight at a time with AVX2 where the processor has it,
// or plain loops elsewhere: the same floats) in straight-line code that reads memory in order: no chain of
// dependent loads from node to node, which costs a cache miss a level when a window's index is cold. Bounds are
// relative to the boxes' lowest corner, rounded outwards: floats for groups and clusters, and for the boxes
// themselves (most of the memory) 16-bit steps of a 65000th of the extent, half the bytes a query reads. Every
// query widens its bound by a slack far above float rounding, so no box it should report is missed (it may
// report one that misses by a few steps, which callers test exactly anyway). What a query reports does not depend on the clustering: callers that
// need an exact answer break ties by box index themselves.

#include <array>
#include <cassert>
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

  /// Most rays a fan() walk takes.
  static constexpr int kFanRays = 64;
  /// Visits the boxes of `frame` that rays from one `origin` may enter: ray k along the unit directions[k] (at
  /// most kFanRays), entering within bounds[k] (m). visit(box, rays) gets each such box once, in no particular
  /// order, with the rays that may enter it as bits (bit k: ray k), a superset of those that do. Each box is
  /// tested against its bounding ball's cone seen from the origin, one dot product a ray: many rays from one point
  /// (a lidar's scan) share the walk, and the caller can measure a box once for all its rays. `bounds` is read
  /// as the walk goes: a visit may lower its rays' bounds (the nearest hit found so far) to prune the boxes
  /// after it. No allocation.
  template <class Visit>
  void fan(int frame, const Vec3& origin, std::span<const Vec3> directions, const double* bounds, Visit&& visit) const;

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
  /// The branch and bound nearest() and along() share: the groups, then the clusters, then the boxes whose key
  /// (squared distance, ray entry) is within the limit, clusters and boxes taken smallest key first, each visit
  /// tightening the limit. `Keys` measures a level's boxes (measure(level, begin, n, key, out) as within() or
  /// entered() do, against its current limits), gives the current limit for groups and clusters
  /// (cluster_limit()) and for boxes (box_limit()), and takes a visit's new bound (tighten(bound)).
  template <class Keys, class Visit>
  void best_first(int frame, Keys& keys, Visit&& visit) const;
  /// A fan's rays for cones(): directions and bounds (rounded up) in floats, side by side.
  struct FanRays {
    alignas(16) float x[kFanRays], y[kFanRays], z[kFanRays], bound[kFanRays];
    float origin[3];  ///< m, relative to the index's origin
    float margin;     ///< m, a ball's widening: the query's slack and float rounding as far as the fan reaches
    float farthest;   ///< m, the largest bound (as it was at the start: bounds only fall)
  };
  /// For each of the boxes [begin, begin + n) of a level (n a multiple of four), in out[0, n), the rays among
  /// `among` that may enter it within their bounds: those whose direction lies in the cone of the box's
  /// bounding ball, when that ball is not entered beyond their bound (all of `among` when the ball holds the
  /// origin; none for an empty box). `scale` turns the level's units into m.
  template <class T>
  static void cones(const FanRays& fan, const Level<T>& level, int begin, int n, float scale, std::uint64_t among,
                    std::uint64_t* out);
  /// A double rounded up to a float (the float is never below it).
  static float round_up(double v) {
    const float f = static_cast<float>(v);
    return static_cast<double>(f) < v ? std::nextafter(f, INFINITY) : f;
  }

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
  // Keys are squared float distances: in m for groups and clusters, in steps for the boxes' level.
  struct Distances {
    const BoxIndex& index;
    float q[3], q_steps[3], to_steps2, limit, limit_steps;
    double reach;
    int measure(const Level<float>& level, int begin, int n, float* d2, std::int32_t* out) const {
      return within(level, begin, n, q, limit, d2, out);
    }
    int measure(const Level<std::uint16_t>& level, int begin, int n, float* d2, std::int32_t* out) const {
      return within(level, begin, n, q_steps, limit_steps, d2, out);
    }
    float cluster_limit() const { return limit; }
    float box_limit() const { return limit_steps; }
    void tighten(double b) {
      limit = index.limit2(b, reach);
      limit_steps = limit * to_steps2 * (1.0f + 1e-6f);
    }
  } keys{*this, {}, {}, 0.0f, 0.0f, 0.0f, (p - Vec3(origin_.data())).cwiseAbs().maxCoeff()};
  relative(p, keys.q);
  const float to_steps = static_cast<float>(1.0 / unit_);
  for (int a = 0; a < 3; ++a) keys.q_steps[a] = keys.q[a] * to_steps;
  keys.to_steps2 = to_steps * to_steps;
  keys.tighten(bound);
  best_first(frame, keys, visit);
}

template <class Visit>
void BoxIndex::along(int frame, const Vec3& origin, const Vec3& direction, double bound, Visit&& visit) const {
  if (size_ == 0 || !(bound >= 0.0)) return;
  // Keys are the ray's entries (m) into the boxes, widened by a slack: rounding the origin, the direction and
  // the boxes to floats moves them by far less than that at the farthest point the ray reaches.
  struct Entries {
    float o[3], d[3], unit, widen, limit;
    int measure(const Level<float>& level, int begin, int n, float* t, std::int32_t* out) const {
      return entered(level, begin, n, o, d, 1.0f, widen, limit, t, out);
    }
    int measure(const Level<std::uint16_t>& level, int begin, int n, float* t, std::int32_t* out) const {
      return entered(level, begin, n, o, d, unit, widen, limit, t, out);
    }
    float cluster_limit() const { return limit; }
    float box_limit() const { return limit; }
    void tighten(double b) { limit = static_cast<float>(b) + widen; }
  } keys{{}, {static_cast<float>(direction.x()), static_cast<float>(direction.y()), static_cast<float>(direction.z())},
         static_cast<float>(unit_), 0.0f, 0.0f};
  relative(origin, keys.o);
  const double reach = (origin - Vec3(origin_.data())).cwiseAbs().maxCoeff() + (std::isfinite(bound) ? bound : extent_);
  keys.widen = static_cast<float>(slack(reach));
  keys.tighten(bound);
  best_first(frame, keys, visit);
}

template <class Visit>
void BoxIndex::fan(int frame, const Vec3& origin, std::span<const Vec3> directions, const double* bounds,
                   Visit&& visit) const {
  const int n = static_cast<int>(directions.size());
  assert(n <= kFanRays);
  if (size_ == 0 || n == 0) return;
  FanRays f;
  std::uint64_t all = 0;
  double farthest = 0.0;
  for (int k = 0; k < kFanRays; ++k) {
    const bool ray = k < n && bounds[k] >= 0.0;  // a NaN or negative bound: no box
    const Vec3 d = k < n ? directions[std::size_t(k)] : Vec3::Zero();
    f.x[k] = static_cast<float>(d.x()), f.y[k] = static_cast<float>(d.y()), f.z[k] = static_cast<float>(d.z());
    f.bound[k] = ray ? round_up(bounds[k]) : -INFINITY;
    if (ray) all |= std::uint64_t{1} << k, farthest = std::max(farthest, bounds[k]);
  }
  if (all == 0) return;
  const double from = (origin - Vec3(origin_.data())).cwiseAbs().maxCoeff();
  for (int a = 0; a < 3; ++a) f.origin[a] = static_cast<float>(origin[a] - origin_[std::size_t(a)]);
  // Coordinates reach |origin| + extent from the index's origin; 16 float epsilons of that (and of the query's
  // slack) exceed what rounding them and the fan's origin moves a ball.
  f.margin = static_cast<float>(slack(from + std::min(farthest, extent_)) + 2e-6 * (1.0 + from + extent_));
  f.farthest = round_up(farthest);
  const Level<float> gr = groups(), cl = clusters();
  const Level<std::uint16_t> bx = boxes(frame);
  const std::int32_t *firsts = first(), *counts = count(), *ids = id();
  const float step = static_cast<float>(unit_);
  alignas(16) std::uint64_t in_group[kMaxGroups], in_cluster[kGroupSize], rays[kClusterSize];
  cones(f, gr, 0, group_count_, 1.0f, all, in_group);
  for (int g = 0; g < group_count_; ++g) {
    if (in_group[g] == 0) continue;
    cones(f, cl, g * kGroupSize, kGroupSize, 1.0f, in_group[g], in_cluster);
    for (int j = 0; j < kGroupSize; ++j) {
      if (in_cluster[j] == 0) continue;
      const int c = g * kGroupSize + j;
      cones(f, bx, firsts[c], counts[c], step, in_cluster[j], rays);
      for (int k = 0; k < counts[c]; ++k) {
        if (rays[k] == 0 || ids[firsts[c] + k] < 0) continue;
        visit(int(ids[firsts[c] + k]), rays[k]);
        for (std::uint64_t bits = rays[k]; bits != 0; bits &= bits - 1) {
          const int q = __builtin_ctzll(bits);
          f.bound[q] = round_up(bounds[q]);
        }
      }
    }
  }
}

template <class Keys, class Visit>
void BoxIndex::best_first(int frame, Keys& keys, Visit&& visit) const {
  const Level<std::uint16_t> bx = boxes(frame);
  const std::int32_t *firsts = first(), *counts = count(), *ids = id();
  alignas(16) float group_key[kMaxGroups], cluster_key[kMaxClusters];
  std::int32_t kept_groups[kMaxGroups], pending[kMaxClusters];
  const int g = keys.measure(groups(), 0, group_count_, group_key, kept_groups);
  int m = 0;
  const Level<float> cl = clusters();
  for (int j = 0; j < g; ++j) {
    const int first_cluster = kept_groups[j] * kGroupSize;
    std::int32_t in[kGroupSize];
    const int k = keys.measure(cl, first_cluster, kGroupSize, cluster_key + first_cluster, in);
    for (int i = 0; i < k; ++i) pending[m++] = first_cluster + in[i];
  }
  // The pending clusters within the limit, taken smallest key first: by then the limit has pruned most of them,
  // so each round picks the smallest pending one and drops those beyond the limit instead of sorting them all.
  // Branch free where the outcome is a coin toss (is this cluster within the limit?).
  alignas(16) float box_key[kClusterSize];
  while (m > 0) {
    int at = 0, kept = 0;
    const float limit = keys.cluster_limit();
    for (int j = 0; j < m; ++j) {
      const std::int32_t c = pending[j];
      const bool within = cluster_key[c] <= limit;
      pending[kept] = c;
      at = within && cluster_key[c] < cluster_key[pending[at]] ? kept : at;
      kept += within;
    }
    m = kept;
    if (m == 0) break;
    const int c = pending[at];
    pending[at] = pending[--m];
    const int from = firsts[c];
    // Its boxes within the limit, smallest key first, likewise: the first visits tighten the limit.
    std::int32_t near[kClusterSize];
    int h = keys.measure(bx, from, counts[c], box_key, near);
    while (h > 0) {
      int best = 0;
      for (int i = 1; i < h; ++i) best = box_key[near[i]] < box_key[near[best]] ? i : best;
      const int k = near[best];
      if (!(box_key[k] <= keys.box_limit())) break;
      near[best] = near[--h];
      if (ids[from + k] < 0) continue;  // a padding slot (only an infinite bound reaches one)
      keys.tighten(visit(int(ids[from + k])));
    }
  }
}

}  // namespace peg3d
