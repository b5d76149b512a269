#pragma once
// An agent's own occupancy map, built only from its scans (issue 38, part 2): OctoMap's sensor model, with its
// cells in a dense grid over the arena instead of a tree.
//
// Each scan is inserted as OctoMap's OccupancyOcTreeBase::insertPointCloud(scan, origin, max_range) inserts it:
// the same float point cloud, the same keys (OctoMap's coordToKeyChecked, and its computeRayKeys traversal step for
// step in the same arithmetic, each cell handled as it is met instead of stored), the same sets
// (every cell a ray crosses is free, the cell of an endpoint within max_range is occupied and wins over free, an
// endpoint beyond max_range carves free space up to max_range only), and the same float log-odds updates with
// OctoMap's clamping. So every cell's log-odds equals what an octomap::OcTree holds after insertPointCloud of the
// same scans (tests/sense/scan_map_test.cpp compares them cell by cell). What differs: cells outside the arena's
// box are not kept (no agent goes there), and a cell is found by an index computation, not a tree descent.
//
// Cells are stored in bricks of 4 x 4 x 4, 64 floats each, so that a ray's consecutive cells share cache lines.
// Cost: 4 bytes a cell of the arena's box at the resolution, rounded up to whole bricks, plus per brick a byte
// (its occupied count, for nearest_occupied) and 32 bytes (a scan's two sets, and the cells at the lower clamp,
// which a ray crosses without an update, in one aligned block): the paper's 35 x 35 x 20 m arena at 0.25 m is
// 141 x 141 x 81 cells in 36 x 36 x 21 bricks, 8.0 MB with the scan lists (bytes()). Built once; clear()
// forgets every cell (a fill) and allocates nothing.

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "core/config_fields.hpp"
#include "geometry/vector.hpp"

namespace octomath {
class Vector3;
}  // namespace octomath
namespace octomap {
class OcTree;
}  // namespace octomap

namespace peg3d::sense {

/// The most cells an agent's map may have (4 bytes each: 256 MB).
inline constexpr long long kMaxMapCells = 1LL << 26;

struct ScanMapConfig {
  bool enabled = false;       ///< the agent builds a map from its lidar's scans (needs a lidar)
  double resolution = 0.25;   ///< m, in [0.02, 5]: a cell's edge
  double prob_hit = 0.7;      ///< in (0.5, 1): P(occupied | an endpoint in the cell) (OctoMap's default)
  double prob_miss = 0.4;     ///< in (0, 0.5): P(occupied | a ray through the cell) (OctoMap's default)
  /// in (0, 0.5): the least occupancy probability a cell keeps (OctoMap's default). Both clamps stay off 0.5,
  /// the threshold between free and occupied: a clamp at it would keep every cell on one side.
  double clamp_min = 0.1192;
  double clamp_max = 0.971;   ///< in (0.5, 1): the most (OctoMap's default)
  /// Cells no scan has touched count as occupied for nearest_occupied (the cautious reading); by default free.
  bool unknown_is_occupied = false;
  /// The map persists over the episodes played on one game state (a run) instead of being cleared by every reset.
  bool persist = false;
  /// Echoes from other agents go into the map as obstacles. By default the rays that met an agent are left out
  /// of the map (as a robot leaves out what it tracks apart): a map of the world, whose cells a pursuer's guard
  /// would otherwise steer it away from its own evader with.
  bool insert_agents = false;
  bool operator==(const ScanMapConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, ScanMapConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.flag("enabled", c.enabled, "the agent builds an occupancy map from its range sensors' scans (a lidar's, a depth camera's)");
  v.number("resolution", c.resolution, Range::closed(0.02, 5.0), "m", "edge of a map cell");
  v.number("prob_hit", c.prob_hit, Range{0.5, 1.0, true, true}, "", "occupancy probability an endpoint gives its cell");
  v.number("prob_miss", c.prob_miss, Range{0.0, 0.5, true, true}, "", "occupancy probability a ray gives a cell it crosses");
  v.number("clamp_min", c.clamp_min, Range{0.0, 0.5, true, true}, "", "least occupancy probability a cell keeps");
  v.number("clamp_max", c.clamp_max, Range{0.5, 1.0, true, true}, "", "most occupancy probability a cell keeps");
  v.flag("unknown_is_occupied", c.unknown_is_occupied,
         "cells no scan has touched count as obstacles for the agent's inputs (default: as free space)");
  v.flag("persist", c.persist,
         "the map persists over the episodes of a run (one game state) instead of living for one episode");
  v.flag("insert_agents", c.insert_agents,
         "rays that met another agent go into the map as obstacles (default: they are left out of it)");
}

/// OctoMap's key of a cell: floor(coordinate / resolution) + 32768 on each axis.
using CellKey = std::array<std::uint16_t, 3>;

/// The nearest occupied cell to a point.
struct OccupiedPoint {
  double distance = 0.0;      ///< m from the point to the cell's cube (0 inside it); the cap when none was found
  Vec3 point = Vec3::Zero();  ///< the cube's point nearest to the query point
  bool found = false;         ///< an occupied cell lies within the cap
};

class ScanMap {
 public:
  /// An empty map of the box [lo, hi] (m). Throws InvalidParameter naming "resolution" when the box has more than
  /// kMaxMapCells cells at that resolution.
  ScanMap(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi);
  ~ScanMap();
  ScanMap(const ScanMap&) = delete;
  ScanMap& operator=(const ScanMap&) = delete;

  const ScanMapConfig& config() const { return config_; }

  /// The cells a map of the box [lo, hi] has at the configuration's resolution.
  static long long cells(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi);
  /// The bytes a new map of the box [lo, hi] holds (bytes() before any scan): what a batch of games budgets.
  static std::size_t bytes_for(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi);
  /// Whether OctoMap's 16-bit keys reach the box [lo, hi]: they number the cells -32768 to 32767 about the origin
  /// on each axis (+-8192 m at 0.25 m); a point beyond wraps to another cell.
  static bool keys_reach(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi);

  /// Forgets every cell: the bricks scans touched go back to a new map's state (a fill of those only).
  void clear();

  /// Makes room for scans of `rays` rays of at most `range` m, so that inserting them allocates nothing.
  void reserve(int rays, double range);

  /// Inserts one scan as insertPointCloud(points, origin, max_range) would (points and origin taken as float, as
  /// an octomap::Pointcloud holds them). A ray that met nothing is passed as an endpoint beyond max_range. No
  /// allocation once the map has seen scans as large.
  void insert(const Vec3& origin, std::span<const Vec3> points, double max_range);

  /// The cell's log-odds (float, as OctoMap keeps it), or NaN when no scan has touched it or it lies outside.
  float log_odds(const CellKey& key) const;
  /// The key of the cell holding p (OctoMap's coordToKey), whether or not it lies inside.
  CellKey key_of(const Vec3& p) const;
  /// The centre of a cell (OctoMap's keyToCoord).
  Vec3 centre(const CellKey& key) const;

  /// The occupied cell (log-odds > 0; with unknown_is_occupied, or unknown) nearest to p within `cap` (m),
  /// measured to its cube; among equally near ones the first in key order (x slowest). Searched brick by brick
  /// (4 x 4 x 4 cells, each with its count of such cells) in shells about p until no nearer brick can remain. No
  /// allocation.
  OccupiedPoint nearest_occupied(const Vec3& p, double cap) const;

  /// Cells any scan has touched.
  long long known_cells() const { return known_; }
  /// Cells whose occupancy probability is above 0.5 (log-odds > 0, OctoMap's isNodeOccupied at its default).
  long long occupied_cells() const { return occupied_; }
  /// Calls f(key, log_odds) for every known cell, brick by brick.
  template <class F>
  void for_each_known(F&& f) const {
    for (std::size_t c = 0; c < cells_.size(); ++c) {
      const float v = cells_[c];
      if (v == v && v != -std::numeric_limits<float>::infinity()) f(key_at(c), v);  // neither unknown nor beyond
    }
  }
  /// Whether the latest insert changed any cell nearest_occupied counts (an occupied one, or with
  /// unknown_is_occupied an unknown one): if not, every nearest_occupied answer is as before it.
  bool last_insert_moved_obstacles() const { return obstacles_moved_; }
  /// Whether the latest insert can have changed nearest_occupied(p, ...)'s distance when it was `d` (m) before: a
  /// cell whose occupancy changed counts only if some point of its cube lies within d of p; with
  /// unknown_is_occupied, whenever last_insert_moved_obstacles() (unknown cells change without a flip).
  bool last_insert_moved_obstacles_within(const Vec3& p, double d) const;
  /// Calls f(key, occupied) for each cell whose occupancy (log-odds > 0) the latest insert changed: how the map
  /// grows, for replays. Empty after clear().
  template <class F>
  void for_each_flip(F&& f) const {
    for (const std::uint32_t c : flips_) f(key_at(c), cells_[c] > 0.0f);
  }
  /// Writes the map as OctoMap's binary `.bt` file (atomically): a tree of the same resolution and sensor model
  /// holding every known cell, pruned, as octomap::OcTree::writeBinary writes it (each cell occupied or free by
  /// OctoMap's occupancy threshold, 0.5). Throws std::runtime_error naming the file when it cannot be written
  /// (as core/atomic_file.hpp does).
  void write_bt(const std::filesystem::path& file) const;

  /// Bytes the map holds (cells, scan sets and key buffer).
  std::size_t bytes() const;

 private:
  CellKey key_at(std::size_t c) const;
  /// Brick b's place in the grid of bricks (x, y, z).
  std::array<std::size_t, 3> brick_at(std::size_t b) const {
    return {b / (bricks_[2] * bricks_[1]), (b / bricks_[2]) % bricks_[1], b % bricks_[2]};
  }
  /// Whether every cell of the brick at (bx, by, bz) lies inside the box.
  bool whole_brick(std::size_t bx, std::size_t by, std::size_t bz) const {
    return (bx + 1) * kBrick <= n_[0] && (by + 1) * kBrick <= n_[1] && (bz + 1) * kBrick <= n_[2];
  }
  /// The storage index of a cell inside the box: bricks of 4 x 4 x 4 cells (x slowest), 64 floats each.
  bool index_of(const CellKey& k, std::size_t& c) const {
    // Unsigned differences: a key below the grid's first wraps to a large value and fails the bound too.
    const std::size_t x = std::uint16_t(k[0] - k0_[0]), y = std::uint16_t(k[1] - k0_[1]), z = std::uint16_t(k[2] - k0_[2]);
    if (x >= n_[0] || y >= n_[1] || z >= n_[2]) return false;
    c = (((x / kBrick) * bricks_[1] + y / kBrick) * bricks_[2] + z / kBrick) * kBrickCells +
        ((x % kBrick) << 4 | (y % kBrick) << 2 | (z % kBrick));
    return true;
  }
  /// Calls visit(c) with the storage index of each cell computeRayKeys(origin, end) gives, in its order, that
  /// lies inside the box; none when it fails.
  template <class F>
  void ray_cells(const octomath::Vector3& origin, const octomath::Vector3& end, F&& visit) const;
  /// Whether cell a comes before cell b in key order (x slowest).
  bool key_before(std::size_t a, std::size_t b) const { return key_at(a) < key_at(b); }

  ScanMapConfig config_;
  std::unique_ptr<octomap::OcTree> keys_;     // an empty tree: OctoMap's key arithmetic and ray keys
  CellKey k0_{};                              // the key of the grid's first cell
  std::array<std::size_t, 3> n_{};            // cells per axis
  static constexpr std::size_t kBrick = 4;       // cells per brick edge
  static constexpr std::size_t kBrickCells = 64;  // cells per brick
  std::vector<float> cells_;                  // log-odds by brick (index_of); NaN: unknown; -inf: beyond the box
  std::array<std::size_t, 3> bricks_{};       // bricks per axis
  std::vector<std::uint8_t> brick_occupied_;  // occupied cells per brick (with unknown_is_occupied: or unknown)
  Vec3 corner_ = Vec3::Zero();                // m, the lower corner of the grid's first cell
  /// A brick's cells as bits (bit l: cell l of the brick): a scan's two sets, and the cells at the lower clamp.
  /// Side by side, so that a ray's step into a brick reads one cache line of them.
  struct alignas(32) BrickBits {
    std::uint64_t free = 0, hit = 0, at_min = 0;
  };
  std::vector<BrickBits> bits_;                      // per brick
  std::vector<std::uint32_t> free_list_, hit_list_;  // ... and their cells
  std::vector<std::uint32_t> crossed_;               // every cell a scan's rays cross, in order (repeats kept)
  std::vector<std::uint32_t> flips_;                 // the cells whose occupancy the latest insert changed
  bool obstacles_moved_ = false;                     // the latest insert changed a brick's count of blocked cells
  std::vector<std::uint32_t> touched_;               // the bricks with a known cell, since the map was made or cleared
  std::vector<std::uint8_t> brick_touched_;          // ... 1 for those bricks
  float hit_ = 0.0f, miss_ = 0.0f, min_ = 0.0f, max_ = 0.0f;  // log-odds
  long long known_ = 0, occupied_ = 0;
};

}  // namespace peg3d::sense
