#include "sense/ray_keys.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/cpu.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define PEG3D_RAY_LANES 1
#endif

namespace peg3d::sense {
namespace {

// One ray's state when its traversal starts, as computeRayKeys sets it up: per axis the next border's t, the t
// between borders and the step (as a change of the packed key), the packed keys of its first and last cells, and
// its length (float, as OctoMap keeps it).
struct RayStart {
  double t[3] = {0.0, 0.0, 0.0}, delta[3] = {0.0, 0.0, 0.0};
  std::uint64_t step[3] = {0, 0, 0};
  std::uint64_t first = 0, last = 0;
  double length = 0.0;
  bool traced = false;  // computeRayKeys gives at least the first cell
  std::size_t most = 1;  // the most cells it can give
};

std::uint64_t pack(const octomap::OcTreeKey& k) {
  return (std::uint64_t(k[0]) + kKeyBias) | (std::uint64_t(k[1]) + kKeyBias) << 21 | (std::uint64_t(k[2]) + kKeyBias) << 42;
}

// What computeRayKeys's set-up computes the same for every ray of a scan: the origin's key, and per axis the
// numerator of a ray's first t, (border - origin) with the border half a cell (as a float) above or below the origin
// cell's centre.
struct ScanStart {
  octomap::OcTreeKey origin_key;
  bool origin_ok = false;
  float origin[3] = {0.0f, 0.0f, 0.0f};
  double above[3] = {0.0, 0.0, 0.0}, below[3] = {0.0, 0.0, 0.0};  // a positive and a negative step's numerator
  double resolution = 0.0, factor = 0.0;                           // m, and 1 / m (OctoMap's resolution_factor)
  int max_val = 0;                                                 // OctoMap's tree_max_val
};

ScanStart start_scan(const octomap::OcTree& tree, const octomap::point3d& origin) {
  ScanStart s;
  s.origin_key = octomap::OcTreeKey(0, 0, 0);  // a failed check leaves it part written: then no ray is traced
  s.origin_ok = tree.coordToKeyChecked(origin, s.origin_key);
  s.resolution = tree.getResolution();
  s.factor = 1.0 / s.resolution;  // as OcTreeBaseImpl::setResolution sets resolution_factor
  s.max_val = int(tree.coordToKey(0.0));  // coordToKey(0) = floor(0) + tree_max_val
  const float half = float(1 * s.resolution * 0.5);  // computeRayKeys's float(step * resolution * 0.5), step 1
  for (unsigned i = 0; i < 3; ++i) {
    s.origin[i] = origin(i);
    double up = tree.keyToCoord(s.origin_key[i]), down = up;
    up += half;
    down += -half;
    s.above[i] = up - double(origin(i));
    s.below[i] = down - double(origin(i));
  }
  return s;
}

// OcTreeBaseImpl::computeRayKeys's set-up for the ray from the scan's origin to `end`, in its types and operations
// (what is the same for every ray taken from `s`).
RayStart start_ray(const ScanStart& s, const octomap::OcTree& tree, const octomap::point3d& end) {
  RayStart r;
  octomap::OcTreeKey key_end;
  if (!s.origin_ok || !tree.coordToKeyChecked(end, key_end) || s.origin_key == key_end) return r;
  r.traced = true;
  r.first = pack(s.origin_key);
  r.last = pack(key_end);
  octomap::point3d direction = end - octomap::point3d(s.origin[0], s.origin[1], s.origin[2]);
  const float length = float(direction.norm());
  direction /= length;
  r.length = length;
  for (unsigned i = 0; i < 3; ++i) {
    const int step = direction(i) > 0.0 ? 1 : direction(i) < 0.0 ? -1 : 0;
    r.step[i] = std::uint64_t(std::int64_t(step)) << (21 * i);
    if (step != 0) {
      r.t[i] = (step > 0 ? s.above[i] : s.below[i]) / direction(i);
      r.delta[i] = s.resolution / std::fabs(direction(i));
    } else {
      r.t[i] = r.delta[i] = std::numeric_limits<double>::max();
    }
  }
  r.most = ray_keys_most(length, s.resolution);
  return r;
}

// computeRayKeys's incremental phase for one ray: the axis whose border comes first (on a tie the higher one),
// until the end's cell or a border beyond the length. Returns the end of what it wrote.
std::uint64_t* step_ray(const RayStart& r, std::uint64_t* out) {
  if (!r.traced) return out;
  double tx = r.t[0], ty = r.t[1], tz = r.t[2];
  std::uint64_t cell = r.first;
  *out++ = cell;
  for (;;) {
    if (tx < ty ? tx < tz : false) {
      cell += r.step[0], tx += r.delta[0];
    } else if (!(tx < ty) && ty < tz) {
      cell += r.step[1], ty += r.delta[1];
    } else {
      cell += r.step[2], tz += r.delta[2];
    }
    if (cell == r.last) return out;
    if (std::min(std::min(tx, ty), tz) > r.length) return out;
    *out++ = cell;
  }
}

#ifdef PEG3D_RAY_LANES
constexpr std::size_t kLanes = 8;  // two sets of four: their steps' latencies overlap

// start_ray for four rays in the lanes of AVX2 registers: the same float and double operations in each lane.
__attribute__((target("avx2"))) void start_four(const ScanStart& s, const octomap::point3d* ends, RayStart* out) {
  alignas(16) float e[3][4];
  for (std::size_t k = 0; k < 4; ++k) {
    for (unsigned i = 0; i < 3; ++i) e[i][k] = ends[k](i);
  }
  // The ends' keys: (int) floor(resolution_factor * coordinate) + tree_max_val, checked within [0, 2 tree_max_val).
  __m128i key[3];
  __m128i ok = _mm_set1_epi32(s.origin_ok ? -1 : 0);
  for (unsigned i = 0; i < 3; ++i) {
    const __m256d c = _mm256_cvtps_pd(_mm_load_ps(e[i]));
    key[i] = _mm_add_epi32(_mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_mul_pd(_mm256_set1_pd(s.factor), c))),
                           _mm_set1_epi32(s.max_val));
    ok = _mm_and_si128(ok, _mm_andnot_si128(_mm_cmplt_epi32(key[i], _mm_setzero_si128()),
                                            _mm_cmplt_epi32(key[i], _mm_set1_epi32(2 * s.max_val))));
  }
  __m128i same = _mm_set1_epi32(-1);
  for (unsigned i = 0; i < 3; ++i) same = _mm_and_si128(same, _mm_cmpeq_epi32(key[i], _mm_set1_epi32(s.origin_key[i])));
  // The direction in floats, its length (norm_sq in float, its root in double, kept as a float) and the unit
  // direction (each component divided by the float length).
  __m128 d[3];
  for (unsigned i = 0; i < 3; ++i) d[i] = _mm_sub_ps(_mm_load_ps(e[i]), _mm_set1_ps(s.origin[i]));
  const __m128 squares = _mm_add_ps(_mm_add_ps(_mm_mul_ps(d[0], d[0]), _mm_mul_ps(d[1], d[1])), _mm_mul_ps(d[2], d[2]));
  const __m128 length = _mm256_cvtpd_ps(_mm256_sqrt_pd(_mm256_cvtps_pd(squares)));
  alignas(32) double t[3][4], delta[3][4], length_d[4], most[4];
  alignas(32) std::int64_t step[3][4];
  const __m256d huge = _mm256_set1_pd(std::numeric_limits<double>::max()), zero = _mm256_setzero_pd();
  for (unsigned i = 0; i < 3; ++i) {
    const __m256d u = _mm256_cvtps_pd(_mm_div_ps(d[i], length));
    const __m256d up = _mm256_cmp_pd(u, zero, _CMP_GT_OQ), down = _mm256_cmp_pd(u, zero, _CMP_LT_OQ);
    const __m256d moves = _mm256_or_pd(up, down);
    const __m256d from = _mm256_blendv_pd(_mm256_set1_pd(s.below[i]), _mm256_set1_pd(s.above[i]), up);
    const __m256d magnitude = _mm256_andnot_pd(_mm256_set1_pd(-0.0), u);
    _mm256_store_pd(t[i], _mm256_blendv_pd(huge, _mm256_div_pd(from, u), moves));
    _mm256_store_pd(delta[i], _mm256_blendv_pd(huge, _mm256_div_pd(_mm256_set1_pd(s.resolution), magnitude), moves));
    const __m256i one = _mm256_set1_epi64x(std::int64_t{1} << (21 * i));
    const __m256i minus = _mm256_set1_epi64x(std::int64_t(~std::uint64_t{0} << (21 * i)));
    _mm256_store_si256(reinterpret_cast<__m256i*>(step[i]),
                       _mm256_or_si256(_mm256_and_si256(_mm256_castpd_si256(up), one),
                                       _mm256_and_si256(_mm256_castpd_si256(down), minus)));
  }
  const __m256d length_lanes = _mm256_cvtps_pd(length);
  _mm256_store_pd(length_d, length_lanes);
  // ray_keys_most: sqrt(3) length / resolution, truncated, + 8.
  _mm256_store_pd(most, _mm256_div_pd(_mm256_mul_pd(_mm256_set1_pd(std::numbers::sqrt3), length_lanes),
                                      _mm256_set1_pd(s.resolution)));
  alignas(16) std::int32_t traced[4], kx[4], ky[4], kz[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(traced), _mm_andnot_si128(same, ok));
  _mm_store_si128(reinterpret_cast<__m128i*>(kx), key[0]);
  _mm_store_si128(reinterpret_cast<__m128i*>(ky), key[1]);
  _mm_store_si128(reinterpret_cast<__m128i*>(kz), key[2]);
  const std::uint64_t first = pack(s.origin_key);
  for (std::size_t k = 0; k < 4; ++k) {
    RayStart& r = out[k];
    if (traced[k] == 0) {
      r = RayStart{};
      continue;
    }
    r.traced = true;
    r.first = first;
    r.last = pack(octomap::OcTreeKey(octomap::key_type(kx[k]), octomap::key_type(ky[k]), octomap::key_type(kz[k])));
    for (unsigned i = 0; i < 3; ++i) r.t[i] = t[i][k], r.delta[i] = delta[i][k], r.step[i] = std::uint64_t(step[i][k]);
    r.length = length_d[k];
    r.most = std::size_t(most[k]) + 8;
  }
}

// Four rays' traversals in the lanes of AVX2 registers.
struct Four {
  __m256d tx, ty, tz, dx, dy, dz, length;
  __m256i cell, last, sx, sy, sz, alive, count;
};

__attribute__((target("avx2"))) void load_four(const RayStart* r, Four& f) {
  alignas(32) double t[3][4], d[3][4], length[4];
  alignas(32) std::uint64_t first[4], last[4], step[3][4];
  alignas(32) std::int64_t alive[4];
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t i = 0; i < 3; ++i) t[i][k] = r[k].t[i], d[i][k] = r[k].delta[i], step[i][k] = r[k].step[i];
    first[k] = r[k].first, last[k] = r[k].last, length[k] = r[k].length;
    alive[k] = r[k].traced ? -1 : 0;
  }
  f.tx = _mm256_load_pd(t[0]), f.ty = _mm256_load_pd(t[1]), f.tz = _mm256_load_pd(t[2]);
  f.dx = _mm256_load_pd(d[0]), f.dy = _mm256_load_pd(d[1]), f.dz = _mm256_load_pd(d[2]);
  f.length = _mm256_load_pd(length);
  f.cell = _mm256_load_si256(reinterpret_cast<const __m256i*>(first));
  f.last = _mm256_load_si256(reinterpret_cast<const __m256i*>(last));
  f.sx = _mm256_load_si256(reinterpret_cast<const __m256i*>(step[0]));
  f.sy = _mm256_load_si256(reinterpret_cast<const __m256i*>(step[1]));
  f.sz = _mm256_load_si256(reinterpret_cast<const __m256i*>(step[2]));
  f.alive = _mm256_load_si256(reinterpret_cast<const __m256i*>(alive));
  f.count = _mm256_sub_epi64(_mm256_setzero_si256(), f.alive);  // the first cell of each traced ray
}

// One step of step_ray in each lane, with masks for its branches: x where tx < ty and tx < tz, y where not
// tx < ty and ty < tz, z elsewhere. A lane not stepping an axis adds +0.0 to its t, which leaves it as it is.
__attribute__((target("avx2"))) inline void step_four(Four& f) {
  const __m256d xy = _mm256_cmp_pd(f.tx, f.ty, _CMP_LT_OQ), xz = _mm256_cmp_pd(f.tx, f.tz, _CMP_LT_OQ),
                yz = _mm256_cmp_pd(f.ty, f.tz, _CMP_LT_OQ);
  const __m256d mx = _mm256_and_pd(xy, xz), my = _mm256_andnot_pd(xy, yz);
  const __m256d mz = _mm256_andnot_pd(_mm256_or_pd(mx, my), _mm256_castsi256_pd(_mm256_set1_epi64x(-1)));
  f.tx = _mm256_add_pd(f.tx, _mm256_and_pd(mx, f.dx));
  f.ty = _mm256_add_pd(f.ty, _mm256_and_pd(my, f.dy));
  f.tz = _mm256_add_pd(f.tz, _mm256_and_pd(mz, f.dz));
  const __m256i step = _mm256_or_si256(_mm256_or_si256(_mm256_and_si256(_mm256_castpd_si256(mx), f.sx),
                                                        _mm256_and_si256(_mm256_castpd_si256(my), f.sy)),
                                       _mm256_and_si256(_mm256_castpd_si256(mz), f.sz));
  f.cell = _mm256_add_epi64(f.cell, step);
  const __m256d least = _mm256_min_pd(_mm256_min_pd(f.tx, f.ty), f.tz);
  const __m256i stop = _mm256_or_si256(_mm256_cmpeq_epi64(f.cell, f.last),
                                       _mm256_castpd_si256(_mm256_cmp_pd(least, f.length, _CMP_GT_OQ)));
  f.alive = _mm256_andnot_si256(stop, f.alive);
  f.count = _mm256_sub_epi64(f.count, f.alive);
}

// Eight rays stepped together: row j of out holds each lane's cell after j steps (a lane's cells are its first
// count[k] rows); at most `rows` rows. Returns the counts.
__attribute__((target("avx2"))) void step_eight(const RayStart* r, std::uint64_t* out, std::size_t rows,
                                                std::uint32_t* count) {
  Four a, b;
  load_four(r, a);
  load_four(r + 4, b);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), a.cell);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 4), b.cell);
  for (std::size_t row = 1; row < rows; ++row) {
    const __m256i any = _mm256_or_si256(a.alive, b.alive);
    if (_mm256_testz_si256(any, any)) break;
    step_four(a);
    step_four(b);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + row * kLanes), a.cell);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + row * kLanes + 4), b.cell);
  }
  assert(_mm256_testz_si256(_mm256_or_si256(a.alive, b.alive), _mm256_or_si256(a.alive, b.alive)));
  alignas(32) std::int64_t counts[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(counts), a.count);
  _mm256_store_si256(reinterpret_cast<__m256i*>(counts + 4), b.count);
  for (std::size_t k = 0; k < kLanes; ++k) count[k] = std::uint32_t(counts[k]);
}
#endif

}  // namespace

bool vector_lanes_available() {
#ifdef PEG3D_RAY_LANES
  return cpu_has_avx2();
#else
  return false;
#endif
}

std::size_t trace_rays(const octomap::OcTree& tree, const octomap::point3d& origin,
                       std::span<const octomap::point3d> ends, std::vector<std::uint64_t>& keys,
                       std::vector<RayKeySpan>& spans, RayLanes lanes) {
  spans.resize(ends.size());
  std::size_t used = 0;
  // keys' size is its room: it grows (doubling) when a scan needs more, and is written through a pointer.
  const auto room = [&](std::size_t n) {
    if (used + n > keys.size()) keys.resize(std::max(used + n, 2 * keys.size()));
    return keys.data() + used;
  };
  if (lanes == RayLanes::kVector && !vector_lanes_available()) {
    throw std::invalid_argument("trace_rays: vector lanes asked for, and this processor has no AVX2");
  }
  const bool vector = lanes == RayLanes::kVector || (lanes == RayLanes::kBest && vector_lanes_available());
  const ScanStart scan = start_scan(tree, origin);
#ifdef PEG3D_RAY_LANES
  if (vector) {
    for (std::size_t g = 0; g < ends.size(); g += kLanes) {
      RayStart r[kLanes];
      const std::size_t n = std::min(kLanes, ends.size() - g);
      std::size_t k = 0;
      for (; k + 4 <= n; k += 4) start_four(scan, ends.data() + g + k, r + k);
      for (; k < n; ++k) r[k] = start_ray(scan, tree, ends[g + k]);
      std::size_t rows = 1;
      for (k = 0; k < n; ++k) rows = std::max(rows, r[k].most + 1);
      std::uint32_t count[kLanes];
      step_eight(r, room(rows * kLanes), rows, count);
      std::size_t written = 1;
      for (std::size_t k = 0; k < n; ++k) {
        spans[g + k] = {std::uint32_t(used + k), std::uint32_t(kLanes), count[k]};
        written = std::max<std::size_t>(written, count[k] + 1);
      }
      used += written * kLanes;  // the rows after every lane's last cell are not kept
    }
    return used;
  }
#endif
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const RayStart r = start_ray(scan, tree, ends[i]);
    std::uint64_t* at = room(r.most);
    const auto count = std::size_t(step_ray(r, at) - at);
    assert(count <= r.most);
    spans[i] = {std::uint32_t(used), 1, std::uint32_t(count)};
    used += count;
  }
  return used;
}

}  // namespace peg3d::sense
