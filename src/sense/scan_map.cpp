#include "sense/scan_map.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <limits>

#include "core/atomic_file.hpp"
#include "core/validation.hpp"

namespace peg3d::sense {
namespace {

constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();
// Cells of a brick that lie beyond the box: neither unknown nor known.
constexpr float kOutside = -std::numeric_limits<float>::infinity();


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
  const CellKey a = key_of(lo), b = key_of(hi);
  long long cells = 1;
  for (int d = 0; d < 3; ++d) {
    k0_[std::size_t(d)] = a[std::size_t(d)];
    n_[std::size_t(d)] = std::size_t(b[std::size_t(d)] - a[std::size_t(d)] + 1);
    cells *= static_cast<long long>(n_[std::size_t(d)]);
  }
  if (cells > kMaxMapCells) {
    throw InvalidParameter("resolution", std::to_string(config.resolution),
                           "gives the arena's map " + std::to_string(cells) + " cells, more than 2^26 (256 MB): choose a coarser one");
  }
  for (int d = 0; d < 3; ++d) bricks_[std::size_t(d)] = (n_[std::size_t(d)] + kBrick - 1) / kBrick;
  const std::size_t bricks = bricks_[0] * bricks_[1] * bricks_[2];
  cells_.resize(bricks * kBrickCells);
  brick_occupied_.resize(bricks);
  bits_.assign(bricks, BrickBits{});
  brick_touched_.assign(bricks, 0);
  touched_.reserve(bricks);
  corner_ = centre(k0_) - Vec3::Constant(0.5 * config.resolution);
  // Every cell unknown; the cells of the last bricks that lie beyond the box are marked kOutside, never known.
  std::fill(cells_.begin(), cells_.end(), kUnknown);
  for (std::size_t bx = 0; bx < bricks_[0]; ++bx) {
    for (std::size_t by = 0; by < bricks_[1]; ++by) {
      for (std::size_t bz = 0; bz < bricks_[2]; ++bz) {
        const std::size_t b = (bx * bricks_[1] + by) * bricks_[2] + bz;
        int inside = kBrickCells;
        if (!whole_brick(bx, by, bz)) {
          inside = 0;
          for (std::size_t l = 0; l < kBrickCells; ++l) {
            const bool in = bx * kBrick + (l >> 4) < n_[0] && by * kBrick + ((l >> 2) & 3) < n_[1] && bz * kBrick + (l & 3) < n_[2];
            if (!in) cells_[b * kBrickCells + l] = kOutside;
            inside += in;
          }
        }
        // The brick's count of blocked cells: none is occupied; with unknown_is_occupied every inside one is.
        brick_occupied_[b] = config_.unknown_is_occupied ? std::uint8_t(inside) : 0;
      }
    }
  }
}

ScanMap::~ScanMap() = default;

long long ScanMap::cells(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi) {
  // OctoMap's coordToKey: floor(coordinate * (1 / resolution)).
  const double factor = 1.0 / config.resolution;
  long long cells = 1;
  for (int d = 0; d < 3; ++d) cells *= static_cast<long long>(std::floor(factor * hi[d]) - std::floor(factor * lo[d])) + 1;
  return cells;
}

std::size_t ScanMap::bytes_for(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi) {
  // As the constructor lays the cells out: whole bricks of kBrick^3 cells, a float each, and per brick its flags.
  const double factor = 1.0 / config.resolution;
  std::size_t bricks = 1;
  for (int d = 0; d < 3; ++d) {
    const auto n = std::size_t(std::floor(factor * hi[d]) - std::floor(factor * lo[d])) + 1;
    bricks *= (n + kBrick - 1) / kBrick;
  }
  return bricks * (kBrickCells * sizeof(float) + 2 + sizeof(BrickBits));
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

void ScanMap::clear() {
  // Only the bricks a scan made a cell known in differ from a new map's: each goes back to unknown cells (those
  // beyond the box stay kOutside), no cell at the clamp, and its count of blocked cells.
  for (const std::uint32_t b : touched_) {
    float* cell = cells_.data() + std::size_t(b) * kBrickCells;
    const auto [bx, by, bz] = brick_at(b);
    int inside = kBrickCells;
    if (whole_brick(bx, by, bz)) {
      std::fill(cell, cell + kBrickCells, kUnknown);  // a brick wholly inside the box (most): a plain fill
    } else {
      inside = 0;
      for (std::size_t l = 0; l < kBrickCells; ++l) {
        const bool in = cell[l] != kOutside;
        if (in) cell[l] = kUnknown;
        inside += in;
      }
    }
    bits_[b].at_min = 0;
    brick_occupied_[b] = config_.unknown_is_occupied ? std::uint8_t(inside) : 0;
    brick_touched_[b] = 0;
  }
  touched_.clear();
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
  const auto most = std::size_t(std::min(double(cells_.size()), double(rays) * per_ray));
  free_list_.reserve(most);
  crossed_.reserve(most);
  hit_list_.reserve(std::min(cells_.size(), std::size_t(rays)));
  flips_.reserve(free_list_.capacity() + hit_list_.capacity());  // every changed cell is in one of the lists
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
  const auto [bx, by, bz] = brick_at(c / kBrickCells);
  return {std::uint16_t(k0_[0] + bx * kBrick + (l >> 4)), std::uint16_t(k0_[1] + by * kBrick + ((l >> 2) & 3)),
          std::uint16_t(k0_[2] + bz * kBrick + (l & 3))};
}

float ScanMap::log_odds(const CellKey& key) const {
  std::size_t c = 0;
  return index_of(key, c) ? cells_[c] : kUnknown;
}

template <class F>
void ScanMap::ray_cells(const octomap::point3d& origin, const octomap::point3d& end, F&& visit) const {
  // OcTreeBaseImpl::computeRayKeys (Amanatides and Woo's traversal) step for step, in the same types and the same
  // operations, so that it meets the same keys; each is visited as it is met instead of stored.
  octomap::OcTreeKey key_origin, key_end;
  if (!keys_->coordToKeyChecked(origin, key_origin) || !keys_->coordToKeyChecked(end, key_end)) return;
  if (key_origin == key_end) return;
  // The cell's storage index follows the key: per axis, its place in the grid and that axis's share of the index
  // (index_of's brick and place in the brick), updated on the axis each step moves along.
  const std::size_t stride[3] = {bricks_[1] * bricks_[2] * kBrickCells, bricks_[2] * kBrickCells, kBrickCells};
  long place[3];
  std::size_t share[3];
  unsigned outside = 0;  // bit i: the cell lies beyond the box on axis i
  const auto locate = [&](unsigned i) {
    // A place below the box wraps to a huge unsigned value, beyond it too; its share is then never used.
    share[i] = std::size_t(place[i] >> 2) * stride[i] + (std::size_t(place[i] & 3) << (4 - 2 * i));
    outside = std::size_t(place[i]) >= n_[i] ? outside | 1u << i : outside & ~(1u << i);
  };
  for (unsigned i = 0; i < 3; ++i) {
    place[i] = long(key_origin[i]) - long(k0_[i]);
    locate(i);
  }
  if (outside == 0) visit(share[0] + share[1] + share[2]);
  octomap::point3d direction = end - origin;
  const float length = float(direction.norm());
  direction /= length;
  const double resolution = keys_->getResolution();
  int step[3];
  double t_max[3], t_delta[3];
  octomap::OcTreeKey key = key_origin;
  for (unsigned i = 0; i < 3; ++i) {
    step[i] = direction(i) > 0.0 ? 1 : direction(i) < 0.0 ? -1 : 0;
    if (step[i] != 0) {
      double border = keys_->keyToCoord(key[i]);
      border += float(step[i] * resolution * 0.5);
      t_max[i] = (border - origin(i)) / direction(i);
      t_delta[i] = resolution / std::fabs(direction(i));
    } else {
      t_max[i] = t_delta[i] = std::numeric_limits<double>::max();
    }
  }
  for (;;) {
    const unsigned dim = t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
    key[dim] = octomap::key_type(key[dim] + step[dim]);
    t_max[dim] += t_delta[dim];
    if (key == key_end) return;
    if (std::min(std::min(t_max[0], t_max[1]), t_max[2]) > length) return;  // missed the end's cell: stop
    place[dim] += step[dim];
    locate(dim);
    if (outside == 0) visit(share[0] + share[1] + share[2]);
  }
}

void ScanMap::insert(const Vec3& origin_d, std::span<const Vec3> points, double max_range) {
  const octomap::point3d origin(float(origin_d.x()), float(origin_d.y()), float(origin_d.z()));
  free_list_.clear();
  hit_list_.clear();
  flips_.clear();
  obstacles_moved_ = false;
  // A brick's 64 cells have one word of each set: bit l of word b is cell b * 64 + l.
  const auto mark_hit = [&](const octomap::OcTreeKey& k) {
    std::size_t c = 0;
    if (!index_of({k[0], k[1], k[2]}, c)) return;
    std::uint64_t& word = bits_[c / kBrickCells].hit;
    const std::uint64_t bit = std::uint64_t{1} << (c % kBrickCells);
    if ((word & bit) != 0) return;
    word |= bit;
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
    // Cells at the lower clamp are also a bit of their brick's word: a ray crossing them needs no load of the value.
    const std::uint64_t bit = std::uint64_t{1} << (c % kBrickCells);
    std::uint64_t& at_min = bits_[c / kBrickCells].at_min;
    at_min = next == min_ ? at_min | bit : at_min & ~bit;
    known_ += !was_known;
    if (!was_known && brick_touched_[c / kBrickCells] == 0) {
      brick_touched_[c / kBrickCells] = 1;
      touched_.push_back(std::uint32_t(c / kBrickCells));
    }
    const int change_occupied = int(next > 0.0f) - int(was_occupied);
    occupied_ += change_occupied;
    if (change_occupied != 0) flips_.push_back(c);
    // The brick's count of blocked cells: occupied ones, and with unknown_is_occupied the unknown ones too.
    const int change_blocked = config_.unknown_is_occupied ? int(next > 0.0f) - int(!was_known || was_occupied) : change_occupied;
    if (change_blocked != 0) {
      brick_occupied_[c / kBrickCells] = std::uint8_t(brick_occupied_[c / kBrickCells] + change_blocked);
      obstacles_moved_ = true;
    }
  };
  // OccupancyOcTreeBase::computeUpdate with the key sets as bits over the grid, and each cell updated once, as
  // insertPointCloud updates it. First the occupied set: the endpoints within max_range (they win over free).
  for (const Vec3& pd : points) {
    const octomap::point3d p(float(pd.x()), float(pd.y()), float(pd.z()));
    octomap::OcTreeKey key;
    if ((max_range < 0.0 || (p - origin).norm() <= max_range) && keys_->coordToKeyChecked(p, key)) {
      mark_hit(key);
    }
  }
  // Then every ray's free cells, each updated when first met: a miss, unless it is an endpoint's cell or already
  // at the lower clamp (OctoMap's early abort). The rays are traversed first, each cell's value prefetched as it
  // is found, and the cells updated after, in the same order: the traversal's arithmetic then overlaps the cache
  // misses of a map whose lines other work has evicted (a game's, between scans).
  crossed_.clear();
  const auto cross = [&](std::size_t c) {
    __builtin_prefetch(&cells_[c]);
    crossed_.push_back(std::uint32_t(c));
  };
  for (const Vec3& pd : points) {
    const octomap::point3d p(float(pd.x()), float(pd.y()), float(pd.z()));
    if (max_range < 0.0 || (p - origin).norm() <= max_range) {
      ray_cells(origin, p, cross);
    } else {
      const octomap::point3d direction = (p - origin).normalized();
      ray_cells(origin, origin + direction * float(max_range), cross);
    }
  }
  for (const std::uint32_t c : crossed_) {
    BrickBits& brick = bits_[c / kBrickCells];
    const std::uint64_t bit = std::uint64_t{1} << (c % kBrickCells);
    if (((brick.free | brick.hit | brick.at_min) & bit) != 0) continue;  // met, an endpoint, or no change
    brick.free |= bit;
    free_list_.push_back(c);
    float& v = cells_[c];
    if (v <= 0.0f) {  // known and free (false for unknown, NaN): a miss keeps it free, the counts stand
      v = std::max(v + miss_, min_);
      if (v == min_) brick.at_min |= bit;
      continue;
    }
    update(c, miss_);
  }
  for (std::uint32_t c : free_list_) bits_[c / kBrickCells].free = 0;
  for (std::uint32_t c : hit_list_) {
    update(c, hit_);
    bits_[c / kBrickCells].hit = 0;
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
  std::size_t best_cell = 0;
  // Visits brick (bx, by, bz): its cubes, when the brick holds occupied cells and could hold a nearer one.
  const auto visit = [&](long bx, long by, long bz) {
    if (bx < 0 || by < 0 || bz < 0 || bx >= nb[0] || by >= nb[1] || bz >= nb[2]) return;
    if (brick_occupied_[(std::size_t(bx) * bricks_[1] + std::size_t(by)) * bricks_[2] + std::size_t(bz)] == 0) return;
    const Vec3 lo = corner_ + edge * Vec3(double(bx), double(by), double(bz));
    const Vec3 q = p.cwiseMax(lo).cwiseMin(lo + Vec3::Constant(edge));
    if ((q - p).norm() > best.distance) return;
    const std::size_t b = (std::size_t(bx) * bricks_[1] + std::size_t(by)) * bricks_[2] + std::size_t(bz);
    for (std::size_t l = 0; l < kBrickCells; ++l) {
      const std::size_t c = b * kBrickCells + l;
      const float v = cells_[c];
      if (!(v > 0.0f) && !(unknown_blocks && v != v)) continue;
      const Vec3 centre = lo + res * Vec3(double(l >> 4), double((l >> 2) & 3), double(l & 3)) + Vec3::Constant(half);
      const Vec3 point = p.cwiseMax(centre - Vec3::Constant(half)).cwiseMin(centre + Vec3::Constant(half));
      const double d = (point - p).norm();
      if (d < best.distance || (d == best.distance && best.found && key_before(c, best_cell))) {
        best = {d, point, true};
        best_cell = c;
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
  return cells_.capacity() * sizeof(float) + brick_occupied_.capacity() +
         bits_.capacity() * sizeof(BrickBits) +
         (free_list_.capacity() + crossed_.capacity() + hit_list_.capacity() + flips_.capacity() + touched_.capacity()) *
             sizeof(std::uint32_t) +
         brick_touched_.capacity();
}

}  // namespace peg3d::sense
