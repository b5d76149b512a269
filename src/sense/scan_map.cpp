#include "sense/scan_map.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/validation.hpp"

namespace peg3d::sense {
namespace {

constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();

bool test_and_set(std::vector<std::uint64_t>& bits, std::size_t c) {
  std::uint64_t& word = bits[c >> 6];
  const std::uint64_t bit = std::uint64_t{1} << (c & 63);
  const bool was = (word & bit) != 0;
  word |= bit;
  return was;
}

bool test(const std::vector<std::uint64_t>& bits, std::size_t c) { return (bits[c >> 6] >> (c & 63)) & 1; }

}  // namespace

ScanMap::ScanMap(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi)
    : config_(config), keys_(std::make_unique<octomap::OcTree>(config.resolution)), ray_(std::make_unique<octomap::KeyRay>()) {
  keys_->setProbHit(config.prob_hit);
  keys_->setProbMiss(config.prob_miss);
  keys_->setClampingThresMin(config.clamp_min);
  keys_->setClampingThresMax(config.clamp_max);
  hit_ = keys_->getProbHitLog();
  miss_ = keys_->getProbMissLog();
  min_ = keys_->getClampingThresMinLog();
  max_ = keys_->getClampingThresMaxLog();
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
  cells_.assign(std::size_t(cells), kUnknown);
  for (int d = 0; d < 3; ++d) bricks_[std::size_t(d)] = (n_[std::size_t(d)] + kBrick - 1) / kBrick;
  corner_ = centre(k0_) - Vec3::Constant(0.5 * config.resolution);
  brick_occupied_.resize(bricks_[0] * bricks_[1] * bricks_[2]);
  clear();
  free_bits_.assign((std::size_t(cells) + 63) / 64, 0);
  hit_bits_.assign(free_bits_.size(), 0);
}

ScanMap::~ScanMap() = default;

long long ScanMap::cells(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi) {
  // OctoMap's coordToKey: floor(coordinate * (1 / resolution)).
  const double factor = 1.0 / config.resolution;
  long long cells = 1;
  for (int d = 0; d < 3; ++d) cells *= static_cast<long long>(std::floor(factor * hi[d]) - std::floor(factor * lo[d])) + 1;
  return cells;
}

void ScanMap::clear() {
  std::fill(cells_.begin(), cells_.end(), kUnknown);
  if (config_.unknown_is_occupied) {
    // Every cell is unknown, so blocked: a brick counts the cells it holds.
    for (std::size_t bx = 0; bx < bricks_[0]; ++bx) {
      for (std::size_t by = 0; by < bricks_[1]; ++by) {
        for (std::size_t bz = 0; bz < bricks_[2]; ++bz) {
          const auto span = [&](std::size_t b, std::size_t n) { return std::min(n, (b + 1) * kBrick) - b * kBrick; };
          brick_occupied_[(bx * bricks_[1] + by) * bricks_[2] + bz] =
              std::uint8_t(span(bx, n_[0]) * span(by, n_[1]) * span(bz, n_[2]));
        }
      }
    }
  } else {
    std::fill(brick_occupied_.begin(), brick_occupied_.end(), 0);
  }
  known_ = occupied_ = 0;
}

void ScanMap::reserve(int rays, double range) {
  // A ray crosses at most 3 cells per resolution of its length, and a few at its ends; a scan's lists hold each
  // cell once.
  const double per_ray = 3.0 * std::ceil(range / config_.resolution) + 4.0;
  const auto most = std::size_t(std::min(double(cells_.size()), double(rays) * per_ray));
  free_list_.reserve(most);
  hit_list_.reserve(std::min(cells_.size(), std::size_t(rays)));
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
  const std::size_t z = c % n_[2], y = (c / n_[2]) % n_[1], x = c / (n_[2] * n_[1]);
  return {std::uint16_t(k0_[0] + x), std::uint16_t(k0_[1] + y), std::uint16_t(k0_[2] + z)};
}

bool ScanMap::index_of(const CellKey& k, std::size_t& c) const {
  // Unsigned differences: a key below the grid's first wraps to a large value and fails the bound too.
  const std::size_t x = std::uint16_t(k[0] - k0_[0]), y = std::uint16_t(k[1] - k0_[1]), z = std::uint16_t(k[2] - k0_[2]);
  if (x >= n_[0] || y >= n_[1] || z >= n_[2]) return false;
  c = (x * n_[1] + y) * n_[2] + z;
  return true;
}

float ScanMap::log_odds(const CellKey& key) const {
  std::size_t c = 0;
  return index_of(key, c) ? cells_[c] : kUnknown;
}

void ScanMap::insert(const Vec3& origin_d, std::span<const Vec3> points, double max_range) {
  const octomap::point3d origin(float(origin_d.x()), float(origin_d.y()), float(origin_d.z()));
  free_list_.clear();
  hit_list_.clear();
  const auto mark = [&](const octomap::OcTreeKey& k, std::vector<std::uint64_t>& bits, std::vector<std::uint32_t>& list) {
    std::size_t c = 0;
    if (index_of({k[0], k[1], k[2]}, c) && !test_and_set(bits, c)) list.push_back(std::uint32_t(c));
  };
  // OccupancyOcTreeBase::computeUpdate, point by point, with the key sets as bits over the grid.
  for (const Vec3& pd : points) {
    const octomap::point3d p(float(pd.x()), float(pd.y()), float(pd.z()));
    if (max_range < 0.0 || (p - origin).norm() <= max_range) {
      if (keys_->computeRayKeys(origin, p, *ray_)) {
        for (const octomap::OcTreeKey& k : *ray_) mark(k, free_bits_, free_list_);
      }
      octomap::OcTreeKey key;
      if (keys_->coordToKeyChecked(p, key)) mark(key, hit_bits_, hit_list_);
    } else {
      const octomap::point3d direction = (p - origin).normalized();
      const octomap::point3d end = origin + direction * float(max_range);
      if (keys_->computeRayKeys(origin, end, *ray_)) {
        for (const octomap::OcTreeKey& k : *ray_) mark(k, free_bits_, free_list_);
      }
    }
  }
  // updateNode(key, occupied): log-odds in float, clamped; an endpoint's cell is not also free.
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
    // The brick's count of blocked cells: occupied ones, and with unknown_is_occupied the unknown ones too.
    const int change_blocked = config_.unknown_is_occupied ? int(next > 0.0f) - int(!was_known || was_occupied) : change_occupied;
    if (change_blocked != 0) {
      const std::size_t z = c % n_[2], y = (c / n_[2]) % n_[1], x = c / (n_[2] * n_[1]);
      brick_occupied_[((x / kBrick) * bricks_[1] + y / kBrick) * bricks_[2] + z / kBrick] += std::uint8_t(change_blocked);
    }
  };
  for (std::uint32_t c : free_list_) {
    if (!test(hit_bits_, c)) update(c, miss_);
    free_bits_[c >> 6] = 0;
  }
  for (std::uint32_t c : hit_list_) {
    update(c, hit_);
    hit_bits_[c >> 6] = 0;
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
    for (std::size_t x = std::size_t(bx) * kBrick; x < std::min(n_[0], std::size_t(bx + 1) * kBrick); ++x) {
      for (std::size_t y = std::size_t(by) * kBrick; y < std::min(n_[1], std::size_t(by + 1) * kBrick); ++y) {
        for (std::size_t z = std::size_t(bz) * kBrick; z < std::min(n_[2], std::size_t(bz + 1) * kBrick); ++z) {
          const std::size_t c = (x * n_[1] + y) * n_[2] + z;
          const float v = cells_[c];
          if (!(v > 0.0f) && !(unknown_blocks && v != v)) continue;
          const Vec3 centre = corner_ + res * Vec3(double(x), double(y), double(z)) + Vec3::Constant(half);
          const Vec3 point = p.cwiseMax(centre - Vec3::Constant(half)).cwiseMin(centre + Vec3::Constant(half));
          const double d = (point - p).norm();
          if (d < best.distance || (d == best.distance && best.found && c < best_cell)) {
            best = {d, point, true};
            best_cell = c;
          }
        }
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

std::size_t ScanMap::bytes() const {
  return cells_.capacity() * sizeof(float) + brick_occupied_.capacity() + (free_bits_.capacity() + hit_bits_.capacity()) * sizeof(std::uint64_t) +
         (free_list_.capacity() + hit_list_.capacity()) * sizeof(std::uint32_t) +
         ray_->sizeMax() * sizeof(octomap::OcTreeKey);
}

}  // namespace peg3d::sense
