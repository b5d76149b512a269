#pragma once
// An agent's own occupancy map, built only from its scans (issue 38, part 2): OctoMap's sensor model, with its
// cells in bricks over the arena's box instead of a tree.
//
// Each scan is inserted as OctoMap's OccupancyOcTreeBase::insertPointCloud(scan, origin, max_range) inserts it:
// the same float point cloud, the same keys (OctoMap's coordToKeyChecked, and its computeRayKeys traversal step for
// step in the same arithmetic), the same sets
// (every cell a ray crosses is free, the cell of an endpoint within max_range is occupied and wins over free, an
// endpoint beyond max_range carves free space up to max_range only), and the same float log-odds updates with
// OctoMap's clamping. So every cell's log-odds equals what an octomap::OcTree holds after insertPointCloud of the
// same scans (tests/sense/scan_map_test.cpp compares them cell by cell). What differs: cells outside the arena's
// box are not kept (no agent goes there), and a cell is found by an index computation, not a tree descent.
//
// Cells are stored in bricks of 4 x 4 x 4, 64 floats each, so that a ray's consecutive cells share cache lines,
// and a brick is allocated when a scan first reaches one of its cells (issue 53): a map holds what its agent saw,
// not the arena. Bricks are found through two tables: per chunk of 8 x 8 x 8 bricks (4 bytes each, made with the
// map) the chunk's block of 512 brick slots (2 KB, made when the chunk is first reached). Per allocated brick: 256
// bytes of cells, 64 of marks (a byte per cell: met by a ray of the scan, an endpoint's), its count of occupied
// cells and its place (bytes()); arenas of up to 2^22 bricks also keep a byte per brick of the grid, its count of
// occupied cells, for nearest_occupied. A scan's rays are traversed first, eight at a time (ray_keys.hpp), then
// their keys become cells, then the cells are updated.
// clear() forgets every brick and keeps the memory, so a map that has held as many bricks allocates nothing.

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "core/config_fields.hpp"
#include "geometry/vector.hpp"
#include "sense/ray_keys.hpp"  // also declares octomath::Vector3 and octomap::OcTree

namespace peg3d::sense {

/// The most cells the box of an agent's map may have (its chunk table then takes 8 MB; only what scans reach is
/// allocated): 1 km x 1 km x 100 m at 0.25 m is 6.4e9.
inline constexpr long long kMaxMapCells = 1LL << 36;
/// The most cells a map may hold at once (bricks reached, 64 cells each): 2^32, about 20 GB.
inline constexpr long long kMaxMapHeldCells = 1LL << 32;

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
  /// kMaxMapCells cells at that resolution or lies beyond OctoMap's keys.
  ScanMap(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi);
  ~ScanMap();
  ScanMap(const ScanMap&) = delete;
  ScanMap& operator=(const ScanMap&) = delete;

  const ScanMapConfig& config() const { return config_; }

  /// The cells the box [lo, hi] has at the configuration's resolution.
  static long long cells(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi);
  /// The most bytes a map of the box [lo, hi] can come to: its tables, scan lists for scans of `rays` rays of at
  /// most `range` m, and the bricks reached by at most `scans` such scans (every brick of the box when `scans` is
  /// negative, or when they could reach more): what a batch of games budgets.
  static std::size_t bytes_most(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi, int rays, double range,
                                long long scans);
  /// Whether OctoMap's 16-bit keys reach the box [lo, hi]: they number the cells -32768 to 32767 about the origin
  /// on each axis (+-8192 m at 0.25 m); a point beyond wraps to another cell.
  static bool keys_reach(const ScanMapConfig& config, const Vec3& lo, const Vec3& hi);

  /// Forgets every cell: no brick is held, and their memory is kept for the next scans.
  void clear();

  /// Makes room for scans of `rays` rays of at most `range` m, so that inserting them allocates nothing but the
  /// bricks they are first to reach.
  void reserve(int rays, double range);

  /// Inserts one scan as insertPointCloud(points, origin, max_range) would (points and origin taken as float, as
  /// an octomap::Pointcloud holds them). A ray that met nothing is passed as an endpoint beyond max_range.
  /// Allocates only when the scan reaches more bricks than the map has held since it was made (allocations()).
  /// Throws std::length_error when the map would hold more than kMaxMapHeldCells.
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
  /// Bricks (4 x 4 x 4 cells) the map holds: those a scan reached since it was made or cleared.
  std::size_t held_bricks() const { return brick_of_.size(); }
  /// Calls f(key, log_odds) for every known cell in key order by brick (bricks x slowest, then the brick's cells
  /// x slowest). Allocates nothing: it sorts the bricks in a scratch array of the map's, so two threads must not
  /// call it on one map at once (a map belongs to one game state).
  template <class F>
  void for_each_known(F&& f) const {
    for (const std::uint32_t slot : sorted_slots()) {
      const float* cell = cells_.data() + std::size_t(slot) * kBrickCells;
      for (std::size_t l = 0; l < kBrickCells; ++l) {
        const float v = cell[l];
        if (v == v && v != -std::numeric_limits<float>::infinity()) f(key_at(std::size_t(slot) * kBrickCells + l), v);
      }
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

  /// Bytes the map holds (tables, bricks and scan lists, as allocated).
  std::size_t bytes() const;
  /// The allocations the map has made since it was made (each growth of one of its arrays is one): the rest of a
  /// step loop allocates nothing, and tests tell the map's growth from anything else.
  long long allocations() const { return allocations_; }

 private:
  static constexpr std::size_t kBrick = 4;        // cells per brick edge
  static constexpr std::size_t kBrickCells = 64;  // cells per brick
  static constexpr std::size_t kChunk = 8;        // bricks per chunk edge
  static constexpr std::size_t kChunkBricks = 512;
  static constexpr std::uint32_t kNone = 0xffffffffu;  // no chunk block, no brick slot

  CellKey key_at(std::size_t c) const;
  /// Brick b's place in the grid of bricks (x, y, z).
  std::array<std::size_t, 3> brick_at(std::size_t b) const {
    return {b / (bricks_[2] * bricks_[1]), (b / bricks_[2]) % bricks_[1], b % bricks_[2]};
  }
  /// The cells of brick b that lie inside the box.
  int inside_cells(std::size_t b) const;
  /// Whether every cell of the brick at (bx, by, bz) lies inside the box.
  bool whole_brick(std::size_t bx, std::size_t by, std::size_t bz) const {
    return (bx + 1) * kBrick <= n_[0] && (by + 1) * kBrick <= n_[1] && (bz + 1) * kBrick <= n_[2];
  }
  /// The chunk (8 x 8 x 8 bricks; chunks x slowest) of the brick at (bx, by, bz).
  std::size_t chunk_of(std::size_t bx, std::size_t by, std::size_t bz) const {
    return ((bx / kChunk) * chunks_[1] + by / kChunk) * chunks_[2] + bz / kChunk;
  }
  /// The brick's entry in its chunk's block of 512 slots (x slowest).
  static std::size_t place_in_chunk(std::size_t bx, std::size_t by, std::size_t bz) {
    return (bx % kChunk) << 6 | (by % kChunk) << 3 | (bz % kChunk);
  }
  /// The slot of the brick at (bx, by, bz) inside the grid, or kNone when it is not held.
  std::uint32_t slot_of(std::size_t bx, std::size_t by, std::size_t bz) const {
    const std::uint32_t block = chunk_[chunk_of(bx, by, bz)];
    return block == kNone ? kNone : slot_[std::size_t(block) * kChunkBricks + place_in_chunk(bx, by, bz)];
  }
  /// The slot of the brick at (bx, by, bz), allocated (its cells unknown) when it is not held yet.
  std::uint32_t hold(std::size_t bx, std::size_t by, std::size_t bz);
  /// The storage index (slot * 64 + place in the brick) of the cell at (x, y, z) inside the grid, its brick held.
  std::size_t cell_index(std::uint32_t slot, std::size_t x, std::size_t y, std::size_t z) const {
    return std::size_t(slot) * kBrickCells + ((x % kBrick) << 4 | (y % kBrick) << 2 | (z % kBrick));
  }
  /// The cell's place in the grid when key k lies inside it.
  bool place_of(const CellKey& k, std::size_t& x, std::size_t& y, std::size_t& z) const {
    // Unsigned differences: a key below the grid's first wraps to a large value and fails the bound too.
    x = std::uint16_t(k[0] - k0_[0]), y = std::uint16_t(k[1] - k0_[1]), z = std::uint16_t(k[2] - k0_[2]);
    return x < n_[0] && y < n_[1] && z < n_[2];
  }
  /// Grows v's capacity to at least n (doubling), counting the allocation.
  template <class T>
  void grow(std::vector<T>& v, std::size_t n);
  /// The held bricks' slots in the order of their places in the grid (x slowest), in a scratch array.
  std::span<const std::uint32_t> sorted_slots() const;

  ScanMapConfig config_;
  std::unique_ptr<octomap::OcTree> keys_;     // an empty tree: OctoMap's key arithmetic and ray keys
  CellKey k0_{};                              // the key of the grid's first cell
  std::array<std::size_t, 3> n_{};            // cells per axis
  std::array<std::size_t, 3> bricks_{};       // bricks per axis
  std::array<std::size_t, 3> chunks_{};       // chunks per axis
  Vec3 corner_ = Vec3::Zero();                // m, the lower corner of the grid's first cell
  std::vector<std::uint32_t> chunk_;          // per chunk (x slowest): its block in slot_, or kNone
  std::vector<std::uint32_t> slot_;           // per held chunk, 512 entries (x slowest): each brick's slot or kNone
  std::vector<std::uint32_t> held_chunks_;    // the chunks with a block, to forget them in clear()
  std::vector<std::uint32_t> block_occupied_;  // per block (held chunk): its occupied cells, for nearest_occupied
  // Per slot (a held brick):
  std::vector<float> cells_;                  // 64 log-odds (x slowest); NaN: unknown; -inf: beyond the box
  /// A brick's cells' marks in a scan (a byte per cell, in one cache line): met by a ray, an endpoint's.
  struct alignas(64) BrickMarks {
    std::uint8_t cell[kBrickCells] = {};
  };
  static constexpr std::uint8_t kMarkMet = 1, kMarkHit = 2;
  std::vector<BrickMarks> marks_;
  std::uint8_t& mark_of(std::size_t c) { return marks_[c / kBrickCells].cell[c % kBrickCells]; }
  std::vector<std::uint8_t> brick_occupied_;  // occupied cells (with unknown_is_occupied: or unknown)
  /// The same count per brick of the grid, held or not, when the grid has at most kDenseCountBricks bricks (1 byte
  /// a brick: 27 KB for the paper arena at 0.25 m): nearest_occupied then passes an empty brick with one load.
  std::vector<std::uint8_t> brick_blocked_;
  static constexpr std::size_t kDenseCountBricks = std::size_t{1} << 22;
  std::vector<std::uint32_t> brick_of_;       // its place in the grid of bricks, (bx * by_count + by) * bz_count + bz
  mutable std::vector<std::uint32_t> sorted_;  // scratch of sorted_slots(), as large as brick_of_'s capacity
  std::vector<octomath::Vector3> ends_;               // a scan's rays' ends, as insertPointCloud traces them
  std::vector<std::uint64_t> traced_;                // the keys its rays meet (trace_rays); its size is its room
  std::vector<RayKeySpan> spans_;                    // where each ray's keys lie in traced_
  std::vector<std::uint32_t> hit_list_;              // a scan's endpoints' cells
  std::vector<std::uint32_t> crossed_;               // every cell a scan's rays cross, in order (repeats kept); its
                                                     // size is its capacity
  std::vector<std::uint32_t> flips_;                 // the cells whose occupancy the latest insert changed
  bool obstacles_moved_ = false;                     // the latest insert changed a brick's count of blocked cells
  float hit_ = 0.0f, miss_ = 0.0f, min_ = 0.0f, max_ = 0.0f;  // log-odds
  long long known_ = 0, occupied_ = 0, allocations_ = 0;
};

}  // namespace peg3d::sense
