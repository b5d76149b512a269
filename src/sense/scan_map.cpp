#include "sense/scan_map.hpp"

#include <octomap/OcTree.h>

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
  free_bits_.assign((std::size_t(cells) + 63) / 64, 0);
  hit_bits_.assign(free_bits_.size(), 0);
}

ScanMap::~ScanMap() = default;

void ScanMap::clear() {
  std::fill(cells_.begin(), cells_.end(), kUnknown);
  known_ = occupied_ = 0;
}

CellKey ScanMap::key_of(const Vec3& p) const {
  const octomap::OcTreeKey k = keys_->coordToKey(p.x(), p.y(), p.z());
  return {k[0], k[1], k[2]};
}

Vec3 ScanMap::centre(const CellKey& key) const {
  const octomap::point3d c = keys_->keyToCoord(octomap::OcTreeKey(key[0], key[1], key[2]));
  return {c.x(), c.y(), c.z()};
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
    occupied_ += int(next > 0.0f) - int(was_occupied);
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

std::size_t ScanMap::bytes() const {
  return cells_.capacity() * sizeof(float) + (free_bits_.capacity() + hit_bits_.capacity()) * sizeof(std::uint64_t) +
         (free_list_.capacity() + hit_list_.capacity()) * sizeof(std::uint32_t) +
         ray_->sizeMax() * sizeof(octomap::OcTreeKey);
}

}  // namespace peg3d::sense
