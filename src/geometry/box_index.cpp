#include "geometry/box_index.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <limits>
#include <numeric>
#include <utility>

#include "core/cpu.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define PEG3D_CONE_LANES 1
#endif

namespace peg3d {
namespace {

// A double rounded down to a float (a box's lo; BoxIndex::round_up rounds its hi), so that the float box contains
// the double one.
float down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

// Splits order[begin, end) at median centres along the axis where they spread most, down to ranges of at most
// `size` boxes, appended to `ranges` in order.
void cluster(std::vector<std::int32_t>& order, std::span<const Box> boxes, int begin, int end, int size,
             std::vector<std::pair<int, int>>& ranges) {
  if (end - begin <= size) {
    ranges.emplace_back(begin, end);
    return;
  }
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int k = begin; k < end; ++k) {
    const Vec3 c = boxes[std::size_t(order[std::size_t(k)])].center();
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  int axis = 0;
  const Vec3 spread = hi - lo;
  if (spread.y() > spread[axis]) axis = 1;
  if (spread.z() > spread[axis]) axis = 2;
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](std::int32_t a, std::int32_t b) {
    const double ca = boxes[std::size_t(a)].center()[axis], cb = boxes[std::size_t(b)].center()[axis];
    return ca < cb || (ca == cb && a < b);
  });
  cluster(order, boxes, begin, mid, size, ranges);
  cluster(order, boxes, mid, end, size, ranges);
}

int padded(int n) { return (n + 3) / 4 * 4; }

}  // namespace

BoxIndex::BoxIndex(std::span<const Box> all, int frames) : size_(all.size() / std::size_t(std::max(frames, 1))), frames_(frames) {
  assert(frames >= 1 && all.size() == size_ * std::size_t(frames));
  if (size_ == 0) return;
  assert(size_ <= kMaxBoxes);
  Vec3 lo = all[0].lo, hi = all[0].hi;
  for (const Box& b : all) lo = lo.cwiseMin(b.lo), hi = hi.cwiseMax(b.hi);
  for (int a = 0; a < 3; ++a) origin_[std::size_t(a)] = lo[a];
  extent_ = (hi - lo).maxCoeff();
  // Steps of the boxes' level: the extent in 65000 of them (room for rounding outwards below 65535).
  unit_ = std::max(extent_, 1e-9) / 65000.0;

  // Clusters of the boxes' unions over the frames: they bound every frame's.
  std::vector<Box> boxes(all.begin(), all.begin() + std::ptrdiff_t(size_));
  for (std::size_t f = 1; f < std::size_t(frames); ++f) {
    for (std::size_t i = 0; i < size_; ++i) {
      boxes[i].lo = boxes[i].lo.cwiseMin(all[f * size_ + i].lo);
      boxes[i].hi = boxes[i].hi.cwiseMax(all[f * size_ + i].hi);
    }
  }
  std::vector<std::int32_t> order(size_);
  std::iota(order.begin(), order.end(), 0);
  std::vector<std::pair<int, int>> ranges;
  cluster(order, boxes, 0, static_cast<int>(order.size()), kClusterSize, ranges);
  const int clusters = static_cast<int>(ranges.size());
  cluster_count_ = (clusters + kGroupSize - 1) / kGroupSize * kGroupSize;
  group_count_ = padded(cluster_count_ / kGroupSize);
  slot_count_ = 0;
  for (const auto& [b, e] : ranges) slot_count_ += padded(e - b);

  // Layout (Level): the groups' lo x, y, z, hi x, y, z, the clusters' likewise; each frame's boxes' likewise in
  // steps. An empty slot is an inverted box, which no query meets.
  floats_.assign(6 * (std::size_t(group_count_) + std::size_t(cluster_count_)), 0.0f);
  steps_.assign(6 * std::size_t(frames) * std::size_t(slot_count_), 0);
  ints_.assign(2 * std::size_t(cluster_count_) + std::size_t(slot_count_), -1);
  const auto put = [&](std::size_t offset, int count, int i, const Box* b) {
    for (int a = 0; a < 3; ++a) {
      floats_[offset + std::size_t(a * count + i)] =
          b ? down(b->lo[a] - origin_[std::size_t(a)]) : std::numeric_limits<float>::infinity();
      floats_[offset + std::size_t((3 + a) * count + i)] =
          b ? round_up(b->hi[a] - origin_[std::size_t(a)]) : -std::numeric_limits<float>::infinity();
    }
  };
  const std::size_t cluster_level = 6 * std::size_t(group_count_);
  const auto put_steps = [&](std::size_t offset, int i, const Box* b) {
    for (int a = 0; a < 3; ++a) {
      const double l = b ? std::floor((b->lo[a] - origin_[std::size_t(a)]) / unit_) - 1.0 : 65535.0;
      const double h = b ? std::ceil((b->hi[a] - origin_[std::size_t(a)]) / unit_) + 1.0 : 0.0;
      steps_[offset + std::size_t(a * slot_count_ + i)] = static_cast<std::uint16_t>(std::clamp(l, 0.0, 65535.0));
      steps_[offset + std::size_t((3 + a) * slot_count_ + i)] = static_cast<std::uint16_t>(std::clamp(h, 0.0, 65535.0));
    }
  };
  const Box none{Vec3::Constant(std::numeric_limits<double>::infinity()), Vec3::Constant(-std::numeric_limits<double>::infinity())};
  std::vector<Box> group_bounds(std::size_t(group_count_), none);
  std::int32_t* first = ints_.data();
  std::int32_t* count = first + cluster_count_;
  std::int32_t* id = count + cluster_count_;
  int next = 0;
  for (int c = 0; c < cluster_count_; ++c) {
    first[c] = next;
    count[c] = 0;
    if (c >= clusters) {
      put(cluster_level, cluster_count_, c, nullptr);
      continue;
    }
    const auto [b, e] = ranges[std::size_t(c)];
    Box bounds{Vec3::Constant(std::numeric_limits<double>::infinity()), Vec3::Constant(-std::numeric_limits<double>::infinity())};
    for (int k = 0; k < padded(e - b); ++k) {
      const Box* box = k < e - b ? &boxes[std::size_t(order[std::size_t(b + k)])] : nullptr;
      for (std::size_t f = 0; f < std::size_t(frames); ++f) {
        put_steps(6 * f * std::size_t(slot_count_), next + k, box ? &all[f * size_ + std::size_t(order[std::size_t(b + k)])] : nullptr);
      }
      if (box) {
        id[next + k] = order[std::size_t(b + k)];
        bounds.lo = bounds.lo.cwiseMin(box->lo);
        bounds.hi = bounds.hi.cwiseMax(box->hi);
      }
    }
    put(cluster_level, cluster_count_, c, &bounds);
    Box& group = group_bounds[std::size_t(c / kGroupSize)];
    group.lo = group.lo.cwiseMin(bounds.lo);
    group.hi = group.hi.cwiseMax(bounds.hi);
    count[c] = padded(e - b);
    next += count[c];
  }
  for (int g = 0; g < group_count_; ++g) {
    const Box& bounds = group_bounds[std::size_t(g)];
    put(0, group_count_, g, bounds.lo.x() <= bounds.hi.x() ? &bounds : nullptr);
  }
}

namespace {

#if defined(__SSE2__)
// Four consecutive bounds as floats: floats as they are, steps widened (exactly: they are below 2^16).
__m128 load4(const float* p) { return _mm_loadu_ps(p); }
__m128 load4(const std::uint16_t* p) {
  const __m128i v = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
  return _mm_cvtepi32_ps(_mm_unpacklo_epi16(v, _mm_setzero_si128()));
}
#endif

// cones()'s ray test for one ball: bit q set when ray q's direction lies in the ball's cone (dot >= limit) and its
// bound reaches the ball (bound >= near); m is a multiple of four. Four rays at a time, or, when `wide`, all
// kFanRays eight at a time (AVX2): the same float products and sums in the same order in every lane, so the same bits.
#ifdef PEG3D_CONE_LANES
std::uint64_t rays_in_cone_eight(const float* x, const float* y, const float* z, const float* bound, float cx, float cy,
                                 float cz, float limit, float near);
#endif
std::uint64_t rays_in_cone(const float* x, const float* y, const float* z, const float* bound, int m, float cx,
                           float cy, float cz, float limit, float near, bool wide) {
#ifdef PEG3D_CONE_LANES
  if (wide) {
    assert(m == BoxIndex::kFanRays);
    return rays_in_cone_eight(x, y, z, bound, cx, cy, cz, limit, near);
  }
#else
  (void)wide;
#endif
  std::uint64_t packed = 0;
#if defined(__SSE2__)
  const __m128 vx = _mm_set1_ps(cx), vy = _mm_set1_ps(cy), vz = _mm_set1_ps(cz);
  const __m128 vlimit = _mm_set1_ps(limit), vnear = _mm_set1_ps(near);
  for (int q = 0; q < m; q += 4) {
    const __m128 dot = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_loadu_ps(x + q), vx), _mm_mul_ps(_mm_loadu_ps(y + q), vy)),
                                  _mm_mul_ps(_mm_loadu_ps(z + q), vz));
    const __m128 in = _mm_and_ps(_mm_cmpge_ps(dot, vlimit), _mm_cmpge_ps(_mm_loadu_ps(bound + q), vnear));
    packed |= static_cast<std::uint64_t>(_mm_movemask_ps(in)) << q;
  }
#else
  for (int q = 0; q < m; ++q) {
    const float dot = (x[q] * cx + y[q] * cy) + z[q] * cz;
    if (dot >= limit && bound[q] >= near) packed |= std::uint64_t{1} << q;
  }
#endif
  return packed;
}

#ifdef PEG3D_CONE_LANES
// rays_in_cone() for all kFanRays rays, eight at a time.
__attribute__((target("avx2"))) std::uint64_t rays_in_cone_eight(const float* x, const float* y, const float* z,
                                                                 const float* bound, float cx, float cy, float cz,
                                                                 float limit, float near) {
  const __m256 vx = _mm256_set1_ps(cx), vy = _mm256_set1_ps(cy), vz = _mm256_set1_ps(cz);
  const __m256 vlimit = _mm256_set1_ps(limit), vnear = _mm256_set1_ps(near);
  std::uint64_t packed = 0;
  static_assert(BoxIndex::kFanRays % 8 == 0);
  for (int q = 0; q < BoxIndex::kFanRays; q += 8) {
    const __m256 dot = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(x + q), vx), _mm256_mul_ps(_mm256_loadu_ps(y + q), vy)),
                                     _mm256_mul_ps(_mm256_loadu_ps(z + q), vz));
    const __m256 in = _mm256_and_ps(_mm256_cmp_ps(dot, vlimit, _CMP_GE_OQ), _mm256_cmp_ps(_mm256_loadu_ps(bound + q), vnear, _CMP_GE_OQ));
    packed |= static_cast<std::uint64_t>(_mm256_movemask_ps(in)) << q;
  }
  return packed;
}
#endif

}  // namespace

template <class T>
int BoxIndex::within(const Level<T>& level, int begin, int n, const float q[3], float limit, float* d2, std::int32_t* out) {
  int count = 0;
#if defined(__SSE2__)
  const __m128 qx = _mm_set1_ps(q[0]), qy = _mm_set1_ps(q[1]), qz = _mm_set1_ps(q[2]), zero = _mm_setzero_ps();
  const __m128 bound = _mm_set1_ps(limit);
  const T *lx = level.lo[0] + begin, *ly = level.lo[1] + begin, *lz = level.lo[2] + begin;
  const T *hx = level.hi[0] + begin, *hy = level.hi[1] + begin, *hz = level.hi[2] + begin;
  for (int k = 0; k < n; k += 4) {
    // Per axis max(lo - q, q - hi, 0): the gap outside the box.
    const __m128 x = _mm_max_ps(_mm_max_ps(_mm_sub_ps(load4(lx + k), qx), _mm_sub_ps(qx, load4(hx + k))), zero);
    const __m128 y = _mm_max_ps(_mm_max_ps(_mm_sub_ps(load4(ly + k), qy), _mm_sub_ps(qy, load4(hy + k))), zero);
    const __m128 z = _mm_max_ps(_mm_max_ps(_mm_sub_ps(load4(lz + k), qz), _mm_sub_ps(qz, load4(hz + k))), zero);
    const __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z));
    _mm_storeu_ps(d2 + k, d);
    for (int bits = _mm_movemask_ps(_mm_cmple_ps(d, bound)); bits != 0; bits &= bits - 1) {
      out[count++] = k + __builtin_ctz(static_cast<unsigned>(bits));
    }
  }
#else
  // The same operations one box at a time (max(a, b) as maxps takes it: a > b ? a : b).
  const auto max = [](float a, float b) { return a > b ? a : b; };
  for (int k = 0; k < n; ++k) {
    const int i = begin + k;
    float e[3];
    for (int a = 0; a < 3; ++a) {
      e[a] = max(max(static_cast<float>(level.lo[a][i]) - q[a], q[a] - static_cast<float>(level.hi[a][i])), 0.0f);
    }
    d2[k] = (e[0] * e[0] + e[1] * e[1]) + e[2] * e[2];
    if (d2[k] <= limit) out[count++] = k;
  }
#endif
  return count;
}

template <class T>
void BoxIndex::overlaps(const Level<T>& level, int begin, int n, const float lo[3], const float hi[3], std::int32_t* out) {
  // Boxes meet when on every axis neither lies wholly beyond the other.
  for (int i = begin; i < begin + n; ++i, ++out) {
    bool meets = true;
    for (int a = 0; a < 3; ++a) {
      meets &= !(hi[a] < static_cast<float>(level.lo[a][i])) & !(lo[a] > static_cast<float>(level.hi[a][i]));
    }
    *out = meets ? 1 : 0;
  }
}

template <class T>
int BoxIndex::entered(const Level<T>& level, int begin, int n, const float o[3], const float d[3], float scale,
                      float widen, float limit, float* t, std::int32_t* out) {
  // Per axis the plane the ray crosses first (lo when it heads up the axis, hi down it) and the one it leaves by,
  // each widened outwards. A direction of exactly 0 is taken as a tiny positive one: the slab's planes are then
  // met at -huge or +huge, which is inside or outside the slab as the origin is (touching at 0 when on it).
  const T* near[3];
  const T* far[3];
  float inv[3], near_widen[3], far_widen[3];
  for (int a = 0; a < 3; ++a) {
    const bool up = d[a] >= 0.0f;
    near[a] = (up ? level.lo[a] : level.hi[a]) + begin;
    far[a] = (up ? level.hi[a] : level.lo[a]) + begin;
    inv[a] = 1.0f / (d[a] == 0.0f ? 1e-30f : d[a]);
    near_widen[a] = up ? -widen : widen;
    far_widen[a] = up ? widen : -widen;
  }
  const float inf = std::numeric_limits<float>::infinity();
  int count = 0;
#if defined(__SSE2__)
  const __m128 s = _mm_set1_ps(scale), zero = _mm_setzero_ps(), lim = _mm_set1_ps(limit), never = _mm_set1_ps(inf);
  __m128 ov[3], iv[3], nw[3], fw[3];
  for (int a = 0; a < 3; ++a) {
    ov[a] = _mm_set1_ps(o[a]), iv[a] = _mm_set1_ps(inv[a]);
    nw[a] = _mm_set1_ps(near_widen[a]), fw[a] = _mm_set1_ps(far_widen[a]);
  }
  for (int k = 0; k < n; k += 4) {
    __m128 enter = zero, leave = never;
    for (int a = 0; a < 3; ++a) {
      const __m128 tn = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(_mm_mul_ps(load4(near[a] + k), s), nw[a]), ov[a]), iv[a]);
      const __m128 tf = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(_mm_mul_ps(load4(far[a] + k), s), fw[a]), ov[a]), iv[a]);
      enter = _mm_max_ps(enter, tn);
      leave = _mm_min_ps(leave, tf);
    }
    const __m128 met = _mm_cmple_ps(enter, leave);
    const __m128 at = _mm_or_ps(_mm_and_ps(met, enter), _mm_andnot_ps(met, never));
    _mm_storeu_ps(t + k, at);
    for (int bits = _mm_movemask_ps(_mm_cmple_ps(at, lim)); bits != 0; bits &= bits - 1) {
      out[count++] = k + __builtin_ctz(static_cast<unsigned>(bits));
    }
  }
#else
  // The same operations one box at a time (max(a, b) as maxps takes it: a > b ? a : b).
  const auto max = [](float a, float b) { return a > b ? a : b; };
  const auto min = [](float a, float b) { return a < b ? a : b; };
  for (int k = 0; k < n; ++k) {
    float enter = 0.0f, leave = inf;
    for (int a = 0; a < 3; ++a) {
      enter = max(enter, ((static_cast<float>(near[a][k]) * scale + near_widen[a]) - o[a]) * inv[a]);
      leave = min(leave, ((static_cast<float>(far[a][k]) * scale + far_widen[a]) - o[a]) * inv[a]);
    }
    t[k] = enter <= leave ? enter : inf;
    if (t[k] <= limit) out[count++] = k;
  }
#endif
  return count;
}

template <class T>
void BoxIndex::cones(const FanRays& fan, const Level<T>& level, int begin, int n, float scale, std::uint64_t among,
                     std::uint64_t* out) {
  // Each box's bounding ball seen from the origin, four boxes at a time in floats: its centre c (relative to the
  // origin), the cosine-like limit sqrt(|c|^2 - r^2) that d.c must reach, and the nearest entry |c| - r. The
  // radius is widened by fan.margin, far above the rounding of these floats, and both limits are lowered by
  // far more than the float dot product errs: the test never drops a ray that meets the box.
  alignas(16) float cx[4], cy[4], cz[4], cos_limit[4], entry[4];
  alignas(16) std::int32_t state[4];  // 0: a ray test, 1: the ball holds the origin (every ray), 2: empty box
  // Sparse rays side by side (padded to four with rays that meet nothing), tested without gaps; many as they are.
  // Eight lanes test every ray instead: packing the few cost more than the lanes it spared (BM_WorldScan/2/10).
  alignas(16) float packed_x[kFanRays], packed_y[kFanRays], packed_z[kFanRays], packed_bound[kFanRays];
  std::int8_t ray[kFanRays];
  const float *x = fan.x, *y = fan.y, *z = fan.z, *bound = fan.bound;
  int m = kFanRays;
  const bool wide = cpu_has_avx2();
  const bool sparse = !wide && std::popcount(among) <= kFanRays / 2;
  if (sparse) {
    m = 0;
    for (std::uint64_t bits = among; bits != 0; bits &= bits - 1, ++m) {
      const int q = __builtin_ctzll(bits);
      ray[m] = static_cast<std::int8_t>(q);
      packed_x[m] = fan.x[q], packed_y[m] = fan.y[q], packed_z[m] = fan.z[q], packed_bound[m] = fan.bound[q];
    }
    for (; m % 4 != 0; ++m) ray[m] = 0, packed_x[m] = packed_y[m] = packed_z[m] = 0.0f, packed_bound[m] = -INFINITY;
    x = packed_x, y = packed_y, z = packed_z, bound = packed_bound;
  }
  for (int k = 0; k < n; k += 4) {
    const int i = begin + k;
#if defined(__SSE2__)
    const __m128 s = _mm_set1_ps(scale), half = _mm_set1_ps(0.5f);
    __m128 c[3], d2 = _mm_setzero_ps(), e2 = _mm_setzero_ps(), empty = _mm_setzero_ps();
    for (int a = 0; a < 3; ++a) {
      const __m128 lo = _mm_mul_ps(load4(level.lo[a] + i), s), hi = _mm_mul_ps(load4(level.hi[a] + i), s);
      empty = _mm_or_ps(empty, _mm_cmpgt_ps(lo, hi));
      c[a] = _mm_sub_ps(_mm_mul_ps(_mm_add_ps(lo, hi), half), _mm_set1_ps(fan.origin[a]));
      const __m128 e = _mm_sub_ps(hi, lo);
      d2 = _mm_add_ps(d2, _mm_mul_ps(c[a], c[a]));
      e2 = _mm_add_ps(e2, _mm_mul_ps(e, e));
    }
    const __m128 dist = _mm_sqrt_ps(d2);
    const __m128 r = _mm_add_ps(_mm_mul_ps(_mm_sqrt_ps(e2), half), _mm_set1_ps(fan.margin));
    const __m128 tol = _mm_mul_ps(_mm_add_ps(dist, _mm_set1_ps(1.0f)), _mm_set1_ps(4e-6f));
    const __m128 gap = _mm_mul_ps(_mm_sub_ps(dist, r), _mm_add_ps(dist, r));
    _mm_store_ps(cos_limit, _mm_sub_ps(_mm_sqrt_ps(_mm_max_ps(gap, _mm_setzero_ps())), tol));
    _mm_store_ps(entry, _mm_sub_ps(_mm_sub_ps(dist, r), tol));
    _mm_store_ps(cx, c[0]), _mm_store_ps(cy, c[1]), _mm_store_ps(cz, c[2]);
    const __m128i inside = _mm_and_si128(_mm_castps_si128(_mm_cmple_ps(dist, r)), _mm_set1_epi32(1));
    _mm_store_si128(reinterpret_cast<__m128i*>(state), _mm_or_si128(inside, _mm_and_si128(_mm_castps_si128(empty), _mm_set1_epi32(2))));
#else
    for (int j = 0; j < 4; ++j) {
      float c[3], d2 = 0.0f, e2 = 0.0f;
      bool empty = false;
      for (int a = 0; a < 3; ++a) {
        const float lo = static_cast<float>(level.lo[a][i + j]) * scale, hi = static_cast<float>(level.hi[a][i + j]) * scale;
        empty |= lo > hi;
        c[a] = (lo + hi) * 0.5f - fan.origin[a];
        d2 += c[a] * c[a];
        e2 += (hi - lo) * (hi - lo);
      }
      const float dist = std::sqrt(d2), r = std::sqrt(e2) * 0.5f + fan.margin, tol = (dist + 1.0f) * 4e-6f;
      cos_limit[j] = std::sqrt(std::max((dist - r) * (dist + r), 0.0f)) - tol;
      entry[j] = dist - r - tol;
      cx[j] = c[0], cy[j] = c[1], cz[j] = c[2];
      state[j] = empty ? 2 : dist <= r ? 1 : 0;
    }
#endif
    for (int j = 0; j < 4; ++j) {
      std::uint64_t rays = 0;
      if (state[j] == 1) {
        rays = among;
      } else if (state[j] == 0 && entry[j] <= fan.farthest) {
        // bit q: ray[q] when sparse, else ray q
        std::uint64_t packed = rays_in_cone(x, y, z, bound, m, cx[j], cy[j], cz[j], cos_limit[j], entry[j], wide);
        if (!sparse) {
          rays = packed & among;
        } else {
          for (; packed != 0; packed &= packed - 1) rays |= std::uint64_t{1} << ray[__builtin_ctzll(packed)];
        }
      }
      out[k + j] = rays;
    }
  }
}

template int BoxIndex::within(const Level<float>&, int, int, const float[3], float, float*, std::int32_t*);
template int BoxIndex::within(const Level<std::uint16_t>&, int, int, const float[3], float, float*, std::int32_t*);
template int BoxIndex::entered(const Level<float>&, int, int, const float[3], const float[3], float, float, float, float*,
                               std::int32_t*);
template int BoxIndex::entered(const Level<std::uint16_t>&, int, int, const float[3], const float[3], float, float, float,
                               float*, std::int32_t*);
template void BoxIndex::cones(const FanRays&, const Level<float>&, int, int, float, std::uint64_t, std::uint64_t*);
template void BoxIndex::cones(const FanRays&, const Level<std::uint16_t>&, int, int, float, std::uint64_t, std::uint64_t*);
template void BoxIndex::overlaps(const Level<float>&, int, int, const float[3], const float[3], std::int32_t*);
template void BoxIndex::overlaps(const Level<std::uint16_t>&, int, int, const float[3], const float[3], std::int32_t*);

}  // namespace peg3d
