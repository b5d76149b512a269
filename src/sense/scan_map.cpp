#include "sense/scan_map.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/atomic_file.hpp"
#include "core/validation.hpp"

namespace peg3d::sense {
namespace {

constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();
// Cells of a brick that lie beyond the box: neither unknown nor known.
constexpr float kOutside = -std::numeric_limits<float>::infinity();

// A brick's cells that nearest_occupied counts, a bit each (bit l: cell l): log-odds above 0, or with
// unknown_blocks unknown (NaN); a cell beyond the box (-inf) is neither. Four cells to an SSE2 compare, so that a
// brick's search tests a few cells instead of 64.
std::uint64_t blocked_cells(const float* cell, bool unknown_blocks) {
  std::uint64_t mask = 0;
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps();
  for (int l = 0; l < 64; l += 4) {
    const __m128 v = _mm_loadu_ps(cell + l);
    __m128 in = _mm_cmpgt_ps(v, zero);
    if (unknown_blocks) in = _mm_or_ps(in, _mm_cmpunord_ps(v, v));
    mask |= std::uint64_t(unsigned(_mm_movemask_ps(in))) << l;
  }
#else
  for (int l = 0; l < 64; ++l) {
    const float v = cell[l];
    mask |= std::uint64_t((v > 0.0f) | (unknown_blocks & (v != v))) << l;
  }
#endif
  return mask;
}

}  // namespace

ScanMap::ScanMap(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi)
    : config_(config), keys_(std::make_unique<octomap::OcTree>(config.resolution)) {
  keys_->setProbHit(config.prob_hit);
  keys_->setProbMiss(config.prob_miss);
  keys_->setClampingThresMin(config.clamp_min);
  keys_->setClampingThresMax(config.clamp_max);
  hit_ = keys_->getProbHitLog();
  miss_ = keys_->getProbMissLog();
  min_ = keys_->getClampingThresMinLog();
  max_ = keys_->getClampingThresMaxLog();
  if (!keys_reach(config, lo, hi)) {
    throw InvalidParameter("resolution", std::to_string(config.resolution),
                           "OctoMap's keys do not reach the arena: it lies more than 32768 cells from the origin");
  }
  const long long total = cells(config, lo, hi);
  if (total > kMaxMapCells) {
    throw InvalidParameter("resolution", std::to_string(config.resolution),
                           "gives the arena's map " + std::to_string(total) + " cells, more than 2^36: choose a coarser one");
  }
  const CellKey a = key_of(lo), b = key_of(hi);
  for (std::size_t d = 0; d < 3; ++d) {
    k0_[d] = a[d];
    n_[d] = std::size_t(b[d] - a[d] + 1);
    bricks_[d] = (n_[d] + kBrick - 1) / kBrick;
    chunks_[d] = (bricks_[d] + kChunk - 1) / kChunk;
  }
  chunk_.assign(chunks_[0] * chunks_[1] * chunks_[2], kNone);
  corner_ = centre(k0_) - Vec3::Constant(0.5 * config.resolution);
  if (bricks_[0] * bricks_[1] * bricks_[2] <= kDenseCountBricks) {
    // No brick held: none has an occupied cell; with unknown_is_occupied each has its cells inside the box.
    brick_blocked_.assign(bricks_[0] * bricks_[1] * bricks_[2], 0);
    if (config_.unknown_is_occupied) {
      for (std::size_t b = 0; b < brick_blocked_.size(); ++b) brick_blocked_[b] = std::uint8_t(inside_cells(b));
    }
  }
}

int ScanMap::inside_cells(std::size_t b) const {
  const auto [bx, by, bz] = brick_at(b);
  int inside = 1;
  for (std::size_t d = 0, at[3] = {bx, by, bz}; d < 3; ++d) inside *= int(std::min(kBrick, n_[d] - at[d] * kBrick));
  return inside;
}

ScanMap::~ScanMap() = default;

long long ScanMap::cells(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi) {
  // OctoMap's coordToKey: floor(coordinate * (1 / resolution)).
  const double factor = 1.0 / config.resolution;
  long long cells = 1;
  for (int d = 0; d < 3; ++d) cells *= static_cast<long long>(std::floor(factor * hi[d]) - std::floor(factor * lo[d])) + 1;
  return cells;
}

std::size_t ScanMap::bytes_most(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi, int rays, double range,
                                long long scans) {
  // As the constructor and hold() lay the map out: the chunk table, then per brick reached its cells, marks, count
  // and place, and per chunk reached its block of slots, its count of occupied cells and its place in a list.
  const double factor = 1.0 / config.resolution;
  double bricks = 1.0, chunks = 1.0;
  for (int d = 0; d < 3; ++d) {
    const double n = std::floor(factor * hi[d]) - std::floor(factor * lo[d]) + 1.0;
    bricks *= std::ceil(n / double(kBrick));
    chunks *= std::ceil(n / double(kBrick * kChunk));
  }
  // A ray of length L crosses at most 3 L / e + 4 bricks of edge e (one per face it passes, and its ends').
  const double per_ray = 3.0 * std::ceil(range / (double(kBrick) * config.resolution)) + 4.0;
  const double reached = scans < 0 ? bricks : std::min(bricks, double(scans) * double(rays) * per_ray);
  const double per_brick = double(kBrickCells * sizeof(float) + sizeof(BrickMarks) + 1 + 2 * sizeof(std::uint32_t));
  const double cells_per_ray = 3.0 * std::ceil(range / config.resolution) + 4.0;
  const double traced = double(trace_room(std::size_t(rays), range, config.resolution));
  const double lists = double(rays) * cells_per_ray * 3.0 * sizeof(std::uint32_t) + traced * sizeof(std::uint64_t) +
                       double(rays) * double(sizeof(RayKeySpan) + 3 * sizeof(float));
  const double dense = bricks <= double(kDenseCountBricks) ? bricks : 0.0;
  return std::size_t(chunks * sizeof(std::uint32_t) + dense + reached * per_brick +
                     std::min(chunks, reached) * double((kChunkBricks + 2) * sizeof(std::uint32_t)) + lists);
}

bool ScanMap::keys_reach(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi) {
  const double factor = 1.0 / config.resolution;
  for (int d = 0; d < 3; ++d) {
    for (const double c : {lo[d], hi[d]}) {
      const double cell = std::floor(factor * c);
      if (!(cell >= -32768.0 && cell <= 32767.0)) return false;
    }
  }
  return true;
}

template <class T>
void ScanMap::grow(std::vector<T>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(std::max(n, 2 * v.capacity()));
  ++allocations_;
}

std::uint32_t ScanMap::hold(std::size_t bx, std::size_t by, std::size_t bz) {
  const std::size_t chunk = chunk_of(bx, by, bz);
  if (chunk_[chunk] == kNone) {
    grow(slot_, slot_.size() + kChunkBricks);
    grow(held_chunks_, held_chunks_.size() + 1);
    grow(block_occupied_, block_occupied_.size() + 1);
    chunk_[chunk] = std::uint32_t(slot_.size() / kChunkBricks);
    slot_.resize(slot_.size() + kChunkBricks, kNone);
    held_chunks_.push_back(std::uint32_t(chunk));
    block_occupied_.push_back(0);
  }
  std::uint32_t& entry = slot_[std::size_t(chunk_[chunk]) * kChunkBricks + place_in_chunk(bx, by, bz)];
  if (entry != kNone) return entry;
  const std::size_t slot = brick_of_.size();
  if ((slot + 1) * kBrickCells > std::size_t(kMaxMapHeldCells)) {
    throw std::length_error("an own map would hold more than 2^32 cells");
  }
  if (slot == brick_of_.capacity()) {
    const std::size_t n = std::max<std::size_t>(64, 2 * slot);
    grow(brick_of_, n);
    grow(cells_, n * kBrickCells);
    grow(marks_, n);
    grow(brick_occupied_, n);
    grow(sorted_, n);
  }
  entry = std::uint32_t(slot);
  brick_of_.push_back(std::uint32_t((bx * bricks_[1] + by) * bricks_[2] + bz));
  marks_.push_back(BrickMarks{});
  // Every cell unknown; those of the last bricks that lie beyond the box are marked kOutside, never known.
  cells_.resize(cells_.size() + kBrickCells, kUnknown);
  int inside = kBrickCells;
  if (!whole_brick(bx, by, bz)) {
    inside = 0;
    float* cell = cells_.data() + slot * kBrickCells;
    for (std::size_t l = 0; l < kBrickCells; ++l) {
      const bool in = bx * kBrick + (l >> 4) < n_[0] && by * kBrick + ((l >> 2) & 3) < n_[1] && bz * kBrick + (l & 3) < n_[2];
      if (!in) cell[l] = kOutside;
      inside += in;
    }
  }
  // The brick's count of blocked cells: none is occupied; with unknown_is_occupied every inside one is.
  brick_occupied_.push_back(config_.unknown_is_occupied ? std::uint8_t(inside) : 0);
  return entry;
}

std::span<const std::uint32_t> ScanMap::sorted_slots() const {
  // sorted_ has brick_of_'s capacity: filling it allocates nothing.
  sorted_.resize(brick_of_.size());
  for (std::size_t s = 0; s < sorted_.size(); ++s) sorted_[s] = std::uint32_t(s);
  std::sort(sorted_.begin(), sorted_.end(), [&](std::uint32_t a, std::uint32_t b) { return brick_of_[a] < brick_of_[b]; });
  return sorted_;
}

void ScanMap::clear() {
  if (!brick_blocked_.empty()) {
    for (const std::uint32_t b : brick_of_) brick_blocked_[b] = config_.unknown_is_occupied ? std::uint8_t(inside_cells(b)) : 0;
  }
  for (const std::uint32_t chunk : held_chunks_) chunk_[chunk] = kNone;
  held_chunks_.clear();
  block_occupied_.clear();
  slot_.clear();
  cells_.clear();
  marks_.clear();
  brick_occupied_.clear();
  brick_of_.clear();
  known_ = occupied_ = 0;
  flips_.clear();
  obstacles_moved_ = false;
}

bool ScanMap::last_insert_moved_obstacles_within(const Vec3& p, double d) const {
  if (!obstacles_moved_ || config_.unknown_is_occupied) return obstacles_moved_;
  const double reach = d + 0.5 * std::sqrt(3.0) * config_.resolution + 1e-9;  // cube centre to corner, and slack
  for (const std::uint32_t c : flips_) {
    if ((centre(key_at(c)) - p).squaredNorm() <= reach * reach) return true;
  }
  return false;
}

void ScanMap::reserve(int rays, double range) {
  // A ray crosses at most 3 cells per resolution of its length, and a few at its ends; a scan's lists hold each
  // cell once.
  const double per_ray = 3.0 * std::ceil(range / config_.resolution) + 4.0;
  const auto total = double(n_[0]) * double(n_[1]) * double(n_[2]);
  const auto most = std::size_t(std::min(total, double(rays) * per_ray));
  grow(crossed_, most);
  crossed_.resize(crossed_.capacity());  // written through a pointer: its size is its room
  grow(hit_list_, std::min(most, std::size_t(rays)));
  grow(ends_, std::size_t(rays));
  grow(spans_, std::size_t(rays));
  const std::size_t words = trace_room(std::size_t(rays), range, config_.resolution);  // the rays' keys
  if (words > traced_.size()) {
    grow(traced_, words);
    traced_.resize(traced_.capacity());
  }
  grow(flips_, crossed_.capacity() + hit_list_.capacity());  // every changed cell is in one of the lists
}

CellKey ScanMap::key_of(const Vec3& p) const {
  const octomap::OcTreeKey k = keys_->coordToKey(p.x(), p.y(), p.z());
  return {k[0], k[1], k[2]};
}

Vec3 ScanMap::centre(const CellKey& key) const {
  // Per axis, in double (the point3d overload rounds to float).
  return {keys_->keyToCoord(key[0]), keys_->keyToCoord(key[1]), keys_->keyToCoord(key[2])};
}

CellKey ScanMap::key_at(std::size_t c) const {
  const std::size_t l = c % kBrickCells;
  const auto [bx, by, bz] = brick_at(brick_of_[c / kBrickCells]);
  return {std::uint16_t(k0_[0] + bx * kBrick + (l >> 4)), std::uint16_t(k0_[1] + by * kBrick + ((l >> 2) & 3)),
          std::uint16_t(k0_[2] + bz * kBrick + (l & 3))};
}

float ScanMap::log_odds(const CellKey& key) const {
  std::size_t x = 0, y = 0, z = 0;
  if (!place_of(key, x, y, z)) return kUnknown;
  const std::uint32_t slot = slot_of(x / kBrick, y / kBrick, z / kBrick);
  return slot == kNone ? kUnknown : cells_[cell_index(slot, x, y, z)];
}

void ScanMap::insert(const Vec3& origin_d, std::span<const Vec3> points, double max_range) {
  const octomap::point3d origin(float(origin_d.x()), float(origin_d.y()), float(origin_d.z()));
  hit_list_.clear();
  flips_.clear();
  obstacles_moved_ = false;
  const auto mark_hit = [&](const octomap::OcTreeKey& k) {
    std::size_t x = 0, y = 0, z = 0;
    if (!place_of({k[0], k[1], k[2]}, x, y, z)) return;
    const std::size_t c = cell_index(hold(x / kBrick, y / kBrick, z / kBrick), x, y, z);
    std::uint8_t& mark = mark_of(c);
    if (mark != 0) return;
    mark = kMarkHit;
    grow(hit_list_, hit_list_.size() + 1);
    hit_list_.push_back(std::uint32_t(c));
  };
  // updateNode(key, occupied): log-odds in float, clamped.
  const auto update = [&](std::uint32_t c, float change) {
    float& v = cells_[c];
    const bool was_known = v == v, was_occupied = was_known && v > 0.0f;
    float next = (was_known ? v : 0.0f) + change;
    if (next < min_) next = min_;
    if (next > max_) next = max_;
    v = next;
    known_ += !was_known;
    const int change_occupied = int(next > 0.0f) - int(was_occupied);
    occupied_ += change_occupied;
    if (change_occupied != 0) {
      flips_.push_back(c);
      const auto [bx, by, bz] = brick_at(brick_of_[c / kBrickCells]);
      std::uint32_t& count = block_occupied_[chunk_[chunk_of(bx, by, bz)]];
      count = std::uint32_t(int(count) + change_occupied);
    }
    // The brick's count of blocked cells: occupied ones, and with unknown_is_occupied the unknown ones too.
    const int change_blocked = config_.unknown_is_occupied ? int(next > 0.0f) - int(!was_known || was_occupied) : change_occupied;
    if (change_blocked != 0) {
      brick_occupied_[c / kBrickCells] = std::uint8_t(brick_occupied_[c / kBrickCells] + change_blocked);
      if (!brick_blocked_.empty()) brick_blocked_[brick_of_[c / kBrickCells]] = brick_occupied_[c / kBrickCells];
      obstacles_moved_ = true;
    }
  };
  // OccupancyOcTreeBase::computeUpdate with the key sets as marks on the cells, and each cell updated once, as
  // insertPointCloud updates it. First the occupied set: the endpoints within max_range (they win over free).
  for (const Vec3& pd : points) {
    const octomap::point3d p(float(pd.x()), float(pd.y()), float(pd.z()));
    octomap::OcTreeKey key;
    if ((max_range < 0.0 || (p - origin).norm() <= max_range) && keys_->coordToKeyChecked(p, key)) {
      mark_hit(key);
    }
  }
  // Then every ray's free cells, each updated when first met: a miss, unless it is an endpoint's cell or already
  // at the lower clamp (OctoMap's early abort). The rays are traversed first (several at a time: ray_keys.hpp),
  // then their keys become cells, each cell's value prefetched, and the cells are updated after, in the rays'
  // order: the arithmetic then overlaps the cache misses of a map whose lines other work has evicted (a game's,
  // between scans). The ends are insertPointCloud's: each endpoint, or the point at max_range along its ray.
  grow(ends_, points.size());
  ends_.clear();
  for (const Vec3& pd : points) {
    const octomap::point3d p(float(pd.x()), float(pd.y()), float(pd.z()));
    if (max_range < 0.0 || (p - origin).norm() <= max_range) {
      ends_.push_back(p);
    } else {
      const octomap::point3d direction = (p - origin).normalized();
      ends_.push_back(origin + direction * float(max_range));
    }
  }
  const std::size_t room = traced_.size();
  trace_rays(*keys_, origin, ends_, traced_, spans_);
  allocations_ += traced_.size() != room;
  std::size_t most = 0;
  for (const RayKeySpan& span : spans_) most += span.count;
  if (most > crossed_.size()) {
    grow(crossed_, most);
    crossed_.resize(crossed_.capacity());
  }
  grow(flips_, most + hit_list_.size());
  // A ray's keys met inside the box become its cells' storage indices, their bricks held, each cell's value and
  // mark prefetched for the updates; a ray's cells are updated after the next ray's are found, so that what was
  // prefetched is still in the first-level cache. Every cell's brick is looked up in the tables: a test for the
  // ray entering another brick would be mispredicted every few cells.
  std::size_t crossed = 0;
  const auto unpacked = [](std::uint64_t word) { return CellKey{packed_key(word, 0), packed_key(word, 1), packed_key(word, 2)}; };
  // The table entries of the bricks a ray crosses, fetched into the cache while the ray before it is handled.
  const auto prefetch_slots = [&](const RayKeySpan& span) {
    const std::uint64_t* key = traced_.data() + span.offset;
    for (std::uint32_t j = 0; j < span.count; j += 2, key += 2 * span.stride) {
      std::size_t x = 0, y = 0, z = 0;
      if (!place_of(unpacked(*key), x, y, z)) continue;
      if (const std::uint32_t block = chunk_[chunk_of(x >> 2, y >> 2, z >> 2)]; block != kNone) {
        __builtin_prefetch(&slot_[std::size_t(block) * kChunkBricks + place_in_chunk(x >> 2, y >> 2, z >> 2)]);
      }
    }
  };
  const auto find_cells = [&](const RayKeySpan& span) {
    const std::uint64_t* key = traced_.data() + span.offset;
    for (std::uint32_t j = 0; j < span.count; ++j, key += span.stride) {
      std::size_t x = 0, y = 0, z = 0;
      if (!place_of(unpacked(*key), x, y, z)) continue;
      std::uint32_t slot = slot_of(x >> 2, y >> 2, z >> 2);
      if (slot == kNone) slot = hold(x >> 2, y >> 2, z >> 2);
      const std::size_t c = std::size_t(slot) * kBrickCells + ((x & 3) << 4 | (y & 3) << 2 | (z & 3));
      __builtin_prefetch(&cells_[c]);
      __builtin_prefetch(&mark_of(c));
      crossed_[crossed++] = std::uint32_t(c);
    }
  };
  // Whether a cell is updated (not met before in this scan, not an endpoint's) and whether it was unknown change
  // from cell to cell without a pattern, so the common cases (unknown or known free, and with unknown_is_occupied
  // only known free) are taken without a branch; a cell whose occupancy a miss can change takes update(), which
  // keeps the counts. A cell at the lower clamp is updated to the same value (OctoMap leaves it: the same cell). A
  // byte per cell marks the scan's sets, so that consecutive cells of a brick do not wait on each other's stores.
  const bool unknown_blocks = config_.unknown_is_occupied;
  long long known = 0;
  const auto update_cells = [&](std::size_t from, std::size_t to) {
    for (const std::uint32_t c : std::span(crossed_.data() + from, to - from)) {
      std::uint8_t& mark = mark_of(c);
      float& v = cells_[c];
      const float old = v;
      const bool fresh = mark == 0, was_known = old == old;  // was_known: false for NaN
      mark |= kMarkMet;
      // Bitwise on the conditions, and masks for the choice: the compiler would otherwise branch on them.
      if (fresh & ((old > 0.0f) | (unknown_blocks & !was_known))) {
        update(c, miss_);
        continue;
      }
      const float next = std::max((was_known ? old : 0.0f) + miss_, min_);
      const std::uint32_t keep = std::uint32_t{0} - std::uint32_t(!fresh);
      v = std::bit_cast<float>((std::bit_cast<std::uint32_t>(old) & keep) | (std::bit_cast<std::uint32_t>(next) & ~keep));
      known += std::uint64_t(fresh & !was_known);
    }
  };
  std::size_t updated = 0;
  for (std::size_t r = 0; r < spans_.size(); ++r) {
    const RayKeySpan& span = spans_[r];
    const std::size_t found = crossed;
    if (r + 1 < spans_.size()) prefetch_slots(spans_[r + 1]);
    find_cells(span);
    update_cells(updated, found);
    updated = found;
  }
  update_cells(updated, crossed);
  known_ += known;
  for (const std::uint32_t c : std::span(crossed_.data(), crossed)) mark_of(c) = 0;
  for (std::uint32_t c : hit_list_) {
    update(c, hit_);
    mark_of(c) = 0;
  }
}

OccupiedPoint ScanMap::nearest_occupied(const Vec3& p, double cap) const {
  OccupiedPoint best{cap, Vec3::Zero(), false};
  const bool unknown_blocks = config_.unknown_is_occupied;
  if (occupied_ == 0 && !unknown_blocks) return best;
  const double res = config_.resolution, edge = kBrick * res, half = 0.5 * res;
  const Vec3 rel = (p - corner_) / edge;
  const long b0[3] = {long(std::floor(rel.x())), long(std::floor(rel.y())), long(std::floor(rel.z()))};
  const long nb[3] = {long(bricks_[0]), long(bricks_[1]), long(bricks_[2])};
  CellKey best_key{};
  // Visits brick (bx, by, bz): its cubes, when the brick holds blocked cells and could hold a nearer one. A brick
  // not held has every cell inside the box unknown.
  std::size_t chunk = std::size_t(-1);  // the chunk last looked in, and its block of slots (null: none)
  const std::uint32_t* block = nullptr;
  const bool dense = !brick_blocked_.empty();
  const auto visit = [&](long bx, long by, long bz) {
    if (bx < 0 || by < 0 || bz < 0 || bx >= nb[0] || by >= nb[1] || bz >= nb[2]) return;
    if (dense && brick_blocked_[(std::size_t(bx) * bricks_[1] + std::size_t(by)) * bricks_[2] + std::size_t(bz)] == 0) return;
    const std::size_t ch = chunk_of(std::size_t(bx), std::size_t(by), std::size_t(bz));
    if (ch != chunk) {
      chunk = ch;
      // A chunk without occupied cells holds no nearer one unless unknown cells count.
      block = chunk_[ch] == kNone || (!unknown_blocks && block_occupied_[chunk_[ch]] == 0)
                  ? nullptr
                  : slot_.data() + std::size_t(chunk_[ch]) * kChunkBricks;
    }
    if (block == nullptr && !unknown_blocks) return;
    const std::uint32_t slot = block == nullptr ? kNone : block[place_in_chunk(std::size_t(bx), std::size_t(by), std::size_t(bz))];
    if (slot == kNone ? !unknown_blocks : brick_occupied_[slot] == 0) return;
    const Vec3 lo = corner_ + edge * Vec3(double(bx), double(by), double(bz));
    const Vec3 q = p.cwiseMax(lo).cwiseMin(lo + Vec3::Constant(edge));
    if ((q - p).norm() > best.distance) return;
    // The blocked cells, in the order of l (so among equally near ones the first in key order wins): of a held
    // brick those its bit mask names; of a brick not held (with unknown_is_occupied) every cell inside the box.
    const std::uint64_t blocked = slot == kNone ? ~std::uint64_t{0} : blocked_cells(cells_.data() + std::size_t(slot) * kBrickCells, unknown_blocks);
    for (std::uint64_t bits = blocked; bits != 0; bits &= bits - 1) {
      const auto l = std::size_t(std::countr_zero(bits));
      const std::size_t x = std::size_t(bx) * kBrick + (l >> 4), y = std::size_t(by) * kBrick + ((l >> 2) & 3),
                        z = std::size_t(bz) * kBrick + (l & 3);
      if (x >= n_[0] || y >= n_[1] || z >= n_[2]) continue;  // beyond the box
      const Vec3 centre = lo + res * Vec3(double(l >> 4), double((l >> 2) & 3), double(l & 3)) + Vec3::Constant(half);
      const Vec3 point = p.cwiseMax(centre - Vec3::Constant(half)).cwiseMin(centre + Vec3::Constant(half));
      const double d = (point - p).norm();
      const CellKey key{std::uint16_t(k0_[0] + x), std::uint16_t(k0_[1] + y), std::uint16_t(k0_[2] + z)};
      if (d < best.distance || (d == best.distance && best.found && key < best_key)) {
        best = {d, point, true};
        best_key = key;
      }
    }
  };
  // Shells of bricks about p's: every brick of shell r lies at least (r - 1) brick edges from p.
  const long last = long(std::ceil(cap / edge)) + 1;
  for (long r = 0; r <= last && double(r - 1) * edge <= best.distance; ++r) {
    for (long dx = -r; dx <= r; ++dx) {
      for (long dy = -r; dy <= r; ++dy) {
        const bool face = std::abs(dx) == r || std::abs(dy) == r;
        for (long dz = -r; dz <= r; dz += face || r == 0 ? 1 : 2 * r) visit(b0[0] + dx, b0[1] + dy, b0[2] + dz);
      }
    }
  }
  return best;
}

void ScanMap::write_bt(const std::filesystem::path& file) const {
  octomap::OcTree tree(config_.resolution);
  tree.setProbHit(config_.prob_hit);
  tree.setProbMiss(config_.prob_miss);
  tree.setClampingThresMin(config_.clamp_min);
  tree.setClampingThresMax(config_.clamp_max);
  for_each_known([&](const CellKey& k, float log_odds) { tree.setNodeValue(octomap::OcTreeKey(k[0], k[1], k[2]), log_odds, true); });
  tree.updateInnerOccupancy();
  tree.prune();
  std::ostringstream out;
  if (!tree.writeBinaryConst(out)) throw std::runtime_error(file.string() + ": OctoMap could not write the map");
  write_file_atomically(file, out.str());
}

std::size_t ScanMap::bytes() const {
  const auto held = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return held(chunk_) + held(slot_) + held(held_chunks_) + held(block_occupied_) + held(cells_) + held(marks_) + held(brick_occupied_) + held(brick_blocked_) +
         held(brick_of_) + held(sorted_) + held(ends_) + held(traced_) + held(spans_) + held(hit_list_) +
         held(crossed_) + held(flips_);
}

}  // namespace peg3d::sense
