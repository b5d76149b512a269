#pragma once
// A static bounding-volume hierarchy over axis-aligned boxes: which boxes overlap a query box, and the boxes in
// order of their distance to a point within a bound (branch and bound). It answers the broadphase questions of
// the movers' index (world/mover_timeline.hpp): built once per time window, read by every thread.
//
// Every bound is kept as floats rounded outwards, so a query never misses a box it touches (it may report one
// it misses by a float's rounding, which callers test exactly anyway), and a tree of a thousand boxes fits in
// about 48 KB. What a query reports does not depend on the tree's shape: callers that need an exact answer
// break ties by leaf index themselves.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/vector.hpp"

namespace peg3d {

class BoxTree {
 public:
  BoxTree() = default;
  /// Leaves 0..n-1 are `boxes` (each with lo <= hi).
  explicit BoxTree(std::span<const Box> boxes);

  std::size_t size() const { return leaves_.size(); }
  /// Bytes the tree holds.
  std::size_t bytes() const { return nodes_.capacity() * sizeof(Node) + leaves_.capacity() * sizeof(Leaf); }

  /// Calls visit(leaf) for every leaf whose box meets `query` (closed boxes: touching counts). No allocation.
  template <class Visit>
  void overlapping(const Box& query, Visit&& visit) const;

  /// Visits the leaves whose box lies within `bound` of p (the distance from p to the box, 0 inside), nearer
  /// subtrees first: visit(leaf) returns the new bound (the best distance found so far, or `bound` unchanged),
  /// and subtrees farther than the bound are skipped. No allocation.
  template <class Visit>
  void nearest(const Vec3& p, double bound, Visit&& visit) const;

 private:
  struct Bounds {
    float lo[3], hi[3];
    double distance2(const Vec3& p) const {
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double v = p[a];
        const double e = v < lo[a] ? lo[a] - v : (v > hi[a] ? v - hi[a] : 0.0);
        d2 += e * e;
      }
      return d2;
    }
    bool overlaps(const Box& q) const {
      for (int a = 0; a < 3; ++a) {
        if (q.hi[a] < lo[a] || q.lo[a] > hi[a]) return false;
      }
      return true;
    }
  };
  struct Node {
    Bounds bounds;
    std::int32_t first;  ///< leaf range: its first entry in leaves_; inner: index of the left child (right = first + 1)
    std::int32_t count;  ///< number of leaves (> 0) of a leaf range; 0 for an inner node
  };
  struct Leaf {
    Bounds bounds;
    std::int32_t id;  ///< the box's index as given
  };
  static constexpr int kLeafSize = 4;
  static constexpr int kMaxDepth = 64;

  void build(std::vector<std::int32_t>& order, std::span<const Box> boxes, int slot, int begin, int end, int depth);
  template <class Visit>
  void visit_leaves(const Node& n, const Vec3& p, double& bound, double& bound2, Visit& visit) const {
    for (int k = n.first; k < n.first + n.count; ++k) {
      const Leaf& leaf = leaves_[std::size_t(k)];
      if (leaf.bounds.distance2(p) <= bound2) {
        bound = visit(int(leaf.id));
        bound2 = bound * bound;
      }
    }
  }

  std::vector<Node> nodes_;
  std::vector<Leaf> leaves_;  // in tree order
};

template <class Visit>
void BoxTree::overlapping(const Box& query, Visit&& visit) const {
  if (nodes_.empty()) return;
  std::int32_t stack[kMaxDepth + 2];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[std::size_t(stack[--top])];
    if (!n.bounds.overlaps(query)) continue;
    if (n.count > 0) {
      for (int k = n.first; k < n.first + n.count; ++k) {
        if (leaves_[std::size_t(k)].bounds.overlaps(query)) visit(int(leaves_[std::size_t(k)].id));
      }
      continue;
    }
    stack[top++] = n.first + 1;
    stack[top++] = n.first;
  }
}

template <class Visit>
void BoxTree::nearest(const Vec3& p, double bound, Visit&& visit) const {
  if (nodes_.empty() || !(bound >= 0.0)) return;
  // Depth first, the nearer child first: the bound tightens at the first leaves, and a pending sibling is
  // skipped when it is popped beyond the bound by then. At most one sibling waits per level, so the stack
  // cannot overflow. (A best-first heap pops a few nodes fewer, but each pop costs a sift through the heap.)
  struct Entry {
    double distance2;
    std::int32_t node;
  };
  Entry stack[kMaxDepth + 2];
  int top = 0;
  double bound2 = bound * bound;
  const double root2 = nodes_[0].bounds.distance2(p);
  if (root2 > bound2) return;
  stack[top++] = {root2, 0};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.distance2 > bound2) continue;
    const Node& n = nodes_[std::size_t(e.node)];
    if (n.count > 0) {
      visit_leaves(n, p, bound, bound2, visit);
      continue;
    }
    const std::int32_t l = n.first, r = n.first + 1;
    const double dl = nodes_[std::size_t(l)].bounds.distance2(p), dr = nodes_[std::size_t(r)].bounds.distance2(p);
    const bool left_first = dl <= dr;
    const Entry near_child = left_first ? Entry{dl, l} : Entry{dr, r};
    const Entry far_child = left_first ? Entry{dr, r} : Entry{dl, l};
    if (far_child.distance2 <= bound2) stack[top++] = far_child;
    if (near_child.distance2 <= bound2) stack[top++] = near_child;
  }
}

}  // namespace peg3d
