#include "geometry/box_tree.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace peg3d {
namespace {

// A double rounded down (lo) or up (hi) to a float, so that the float box contains the double one.
float down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

BoxTree::BoxTree(std::span<const Box> boxes) {
  if (boxes.empty()) return;
  std::vector<std::int32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0);
  nodes_.reserve(2 * (boxes.size() / kLeafSize + 1));
  nodes_.push_back({});
  build(order, boxes, 0, 0, static_cast<int>(order.size()), 0);
  leaves_.reserve(boxes.size());
  for (const std::int32_t i : order) {
    const Box& b = boxes[std::size_t(i)];
    Leaf leaf{};
    for (int a = 0; a < 3; ++a) leaf.bounds.lo[a] = down(b.lo[a]), leaf.bounds.hi[a] = up(b.hi[a]);
    leaf.id = i;
    leaves_.push_back(leaf);
  }
}

void BoxTree::build(std::vector<std::int32_t>& order, std::span<const Box> boxes, int slot, int begin, int end,
                    int depth) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Vec3 clo = lo, chi = hi;  // the leaves' centres
  for (int k = begin; k < end; ++k) {
    const Box& b = boxes[std::size_t(order[std::size_t(k)])];
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
    clo = clo.cwiseMin(b.center());
    chi = chi.cwiseMax(b.center());
  }
  Node node{};
  for (int a = 0; a < 3; ++a) node.bounds.lo[a] = down(lo[a]), node.bounds.hi[a] = up(hi[a]);
  if (end - begin <= kLeafSize || depth >= kMaxDepth - 1) {
    node.first = begin;
    node.count = end - begin;
    nodes_[std::size_t(slot)] = node;
    return;
  }
  // Split at the median centre along the axis where the centres spread most.
  int axis = 0;
  const Vec3 spread = chi - clo;
  if (spread.y() > spread[axis]) axis = 1;
  if (spread.z() > spread[axis]) axis = 2;
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](std::int32_t a, std::int32_t b) {
    const double ca = boxes[std::size_t(a)].center()[axis], cb = boxes[std::size_t(b)].center()[axis];
    return ca < cb || (ca == cb && a < b);
  });
  // The children side by side: the left one at `first`, the right one at first + 1.
  node.first = static_cast<int>(nodes_.size());
  node.count = 0;
  nodes_[std::size_t(slot)] = node;
  nodes_.push_back({});
  nodes_.push_back({});
  build(order, boxes, node.first, begin, mid, depth + 1);
  build(order, boxes, node.first + 1, mid, end, depth + 1);
}

}  // namespace peg3d
