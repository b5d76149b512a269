#pragma once
// Ways around solids for scripted players: whether a straight way is passable, and a grid of cells over the arena
// through which a shortest way is found where it is not. What is solid is what the view's SightProbe knows.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "game/policy.hpp"

namespace peg3d::players {

/// m each side of a straight way that must be clear for an agent to fly it (the obstacle guard's stop distance,
/// game/obstacle_guard.hpp).
inline constexpr double kPassage = 0.8;

/// Whether a body can fly straight from a to b: five segments, along the line and `margin` (m) off it on four
/// sides, clear as the probe says.
bool passable(const game::SightProbe& probe, const Vec3& a, const Vec3& b, double margin);

/// A grid over the arena, cells about kCell (m) wide, a cell open where the probe finds no solid within kClearance
/// (m) of its centre, judged once an episode (build(): the solids where they are then), and the open cells joined
/// into regions (26 neighbours). A way between two points is a shortest chain of open cells, each joined to its 26
/// neighbours at the distance of their centres (A*, ties broken by cell index, so the same question gets the same
/// answer). Allocates in build() (per arena size); the search's queue and way grow in waypoint() until they hold the
/// largest search yet, and are reused after that.
class Roadmap {
 public:
  static constexpr double kCell = 1.0;         ///< m, the widest a cell may be (narrower when the arena divides so)
  static constexpr double kClearance = 0.25;   ///< m, from a cell's centre to the nearest solid for it to be open (an agent's radius)
  static constexpr int kMaxCells = 1 << 16;    ///< a larger arena gets wider cells (a roadmap holds about 50 bytes a cell)
  static constexpr int kLookAhead = 6;         ///< cells along the way tried as the point to head for

  /// Cells over `arena`, each judged with `probe`, and their regions.
  void build(const Box& arena, const game::SightProbe& probe);
  /// The point to head for now on a shortest way from `from` to `to`: the farthest of the way's next kLookAhead
  /// cell centres that can be passed to straight (`passable` with `margin`), else the farthest whose straight line
  /// is clear, else the centre of the start's own cell, when that line is clear, else the next one; `to`
  /// itself when they share a cell. The start's cell counts as open whatever it holds (when closed, the way leaves
  /// it only to neighbours whose centres are in plain sight of `from`), and the start's region is its cell's or its
  /// nearest open neighbour's. A goal in a closed cell is taken at the centre of the neighbour
  /// cell of the start's region nearest to it. Nothing when the goal cannot be reached so: in another region
  /// (behind solids all round), or in a closed cell with no such neighbour, or without a start region.
  std::optional<Vec3> waypoint(const game::SightProbe& probe, const Vec3& from, const Vec3& to, double margin);

  /// Shares the open cells out among `sources` (a geodesic Voronoi partition; with `first_speed` != 1, a geodesic
  /// Apollonius one): a cell goes to the source that reaches it first along ways through open cells (26 neighbours
  /// at the distance of their centres, starting from the distance of the source to its own cell's centre, that
  /// cell open or not), the first source moving `first_speed` (> 0) times as fast as the others, each source's
  /// ways passing only through cells it reaches first. A tie goes to the source that reached the cell first, the
  /// same every time. Cells no way reaches, and closed ones but the sources' own, are nobody's (-1). The search
  /// stops once the first source's cells and their neighbours are all decided: farther cells may be left nobody's.
  /// Reuses the search's scratch of waypoint().
  void partition(std::span<const Vec3> sources, double first_speed = 1.0);
  /// The source owning `cell` in the last partition(), -1 for nobody (or undecided, far from the first source).
  int owner(int cell) const { return owner_[std::size_t(cell)]; }
  /// The point of the border between the first source's cells of the last partition() and those of `source`
  /// nearest to the border's centroid: the border is the set of midpoints between two cells sharing a face, one of
  /// each. Nothing when their cells share no face.
  std::optional<Vec3> border_point(int source) const;

  int cells() const { return int(region_.size()); }
  Vec3 centre(int cell) const { return centre_[std::size_t(cell)]; }
  int cell_of(const Vec3& p) const;
  /// The region of an open cell (0, 1, ...), -1 for a closed one.
  int region(int cell) const { return region_[std::size_t(cell)]; }

 private:
  // Calls visit(next, step) for each of the cell's 26 neighbours inside the grid (step: m between the centres).
  template <class F>
  void neighbours(int cell, F&& visit) const;
  // The neighbour of `cell` nearest to p that is open and in `region` (any region for -1); -1 for none.
  int nearest_open(int cell, const Vec3& p, int region) const;
  Box arena_;
  int n_[3] = {0, 0, 0};
  Vec3 size_ = Vec3::Zero();     // m, a cell's extent along each axis
  double step_[27] = {};         // m between the centres of neighbours, by offset (di, dj, dk) + 1 in base 3
  int offset_[27] = {};          // index from a cell to its neighbour, by the same offset
  std::vector<std::uint32_t> inside_;  // per cell: bit o set where the neighbour at offset o is inside the grid
  std::vector<Vec3> centre_;     // per cell
  std::vector<int> region_;      // per cell: its region, -1 closed
  // The last way found (from start_ to goal_, way_.back() the start), kept while both stay in their cells.
  int start_ = -1, goal_ = -1;
  std::vector<int> way_;
  // Scratch of the search, kept between calls (`stamp_` tells this search's entries from older ones).
  std::vector<double> g_, h_;    // m: from the start, and straight on to the goal
  std::vector<int> parent_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t search_ = 0;
  std::vector<std::pair<double, int>> heap_;
  std::vector<int> stack_;
  std::vector<int> owner_;       // per cell: its source in the last partition(), -1 nobody
};

}  // namespace peg3d::players
