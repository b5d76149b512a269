#include "players/roadmap.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>

namespace peg3d::players {

bool passable(const game::SightProbe& probe, const Vec3& a, const Vec3& b, double margin) {
  const Vec3 line = b - a;
  if (!(line.norm() > 0.0)) return true;
  const auto [up, side] = perpendicular_frame(line.normalized());
  for (const Vec3& off : {Vec3(Vec3::Zero()), Vec3(margin * up), Vec3(-margin * up), Vec3(margin * side), Vec3(-margin * side)}) {
    if (!probe.clear(a + off, b + off)) return false;
  }
  return true;
}

template <class F>
void Roadmap::neighbours(int cell, F&& visit) const {
  // The bits of the offsets inside the grid, in the order (dk, dj, di) from (-1, -1, -1) to (1, 1, 1).
  for (std::uint32_t in = inside_[std::size_t(cell)]; in != 0; in &= in - 1) {
    const int o = std::countr_zero(in);
    visit(cell + offset_[o], step_[o]);
  }
}

void Roadmap::build(const Box& arena, const game::SightProbe& probe) {
  arena_ = arena;
  const Vec3 extent = arena.size();
  double cell = kCell;
  auto count = [&](int k) { return std::max(1, int(std::ceil(extent[k] / cell))); };
  while (double(count(0)) * count(1) * count(2) > kMaxCells) cell *= 1.25;
  for (int k = 0; k < 3; ++k) {
    n_[k] = count(k);
    size_[k] = extent[k] / n_[k];
  }
  // Per offset o = (dk + 1) * 9 + (dj + 1) * 3 + (di + 1) to a neighbour: the distance between the centres and the
  // step of the index.
  for (int o = 0; o < 27; ++o) {
    const int di = o % 3 - 1, dj = (o / 3) % 3 - 1, dk = o / 9 - 1;
    step_[o] = Vec3(di * size_.x(), dj * size_.y(), dk * size_.z()).norm();
    offset_[o] = di + n_[0] * (dj + n_[1] * dk);
  }
  const int n = n_[0] * n_[1] * n_[2];
  centre_.resize(std::size_t(n));
  inside_.resize(std::size_t(n));
  for (int c = 0; c < n; ++c) {
    const int ijk[3] = {c % n_[0], (c / n_[0]) % n_[1], c / (n_[0] * n_[1])};
    centre_[std::size_t(c)] =
        arena_.lo + Vec3((ijk[0] + 0.5) * size_.x(), (ijk[1] + 0.5) * size_.y(), (ijk[2] + 0.5) * size_.z());
    std::uint32_t in = 0;
    for (int o = 0; o < 27; ++o) {
      const int d[3] = {o % 3 - 1, (o / 3) % 3 - 1, o / 9 - 1};
      bool inside = o != 13;
      for (int k = 0; k < 3; ++k) inside = inside && ijk[k] + d[k] >= 0 && ijk[k] + d[k] < n_[k];
      in |= std::uint32_t(inside) << o;
    }
    inside_[std::size_t(c)] = in;
  }
  region_.resize(std::size_t(n));
  constexpr int kUnlabelled = -2;
  for (int c = 0; c < n; ++c) region_[std::size_t(c)] = probe.clearance(centre(c)) >= kClearance ? kUnlabelled : -1;
  int regions = 0;  // flood fill, cells in index order
  for (int c = 0; c < n; ++c) {
    if (region_[std::size_t(c)] != kUnlabelled) continue;
    region_[std::size_t(c)] = regions;
    stack_.assign(1, c);
    while (!stack_.empty()) {
      const int top = stack_.back();
      stack_.pop_back();
      neighbours(top, [&](int next, double) {
        if (region_[std::size_t(next)] == kUnlabelled) region_[std::size_t(next)] = regions, stack_.push_back(next);
      });
    }
    ++regions;
  }
  g_.resize(std::size_t(n));
  h_.resize(std::size_t(n));
  parent_.resize(std::size_t(n));
  stamp_.assign(std::size_t(n), 0);
  owner_.assign(std::size_t(n), -1);
  search_ = 0;
  start_ = goal_ = -1;
  way_.clear();
}

int Roadmap::nearest_open(int cell, const Vec3& p, int region) const {
  int best = -1;
  double nearest = std::numeric_limits<double>::infinity();
  neighbours(cell, [&](int next, double) {
    const int r = region_[std::size_t(next)];
    const double d = (centre(next) - p).squaredNorm();
    if (r >= 0 && (region < 0 || r == region) && d < nearest) nearest = d, best = next;
  });
  return best;
}

int Roadmap::cell_of(const Vec3& p) const {
  int c[3];
  for (int k = 0; k < 3; ++k) c[k] = std::clamp(int(std::floor((p[k] - arena_.lo[k]) / size_[k])), 0, n_[k] - 1);
  return c[0] + n_[0] * (c[1] + n_[1] * c[2]);
}

std::optional<Vec3> Roadmap::waypoint(const game::SightProbe& probe, const Vec3& from, const Vec3& to, double margin) {
  const int start = cell_of(from);
  int goal = cell_of(to);
  if (start == goal) return to;
  // The start's region: its cell's, or that of its open neighbour nearest to `from`.
  int home = region_[std::size_t(start)];
  if (home < 0) {
    const int beside = nearest_open(start, from, -1);
    if (beside < 0) return std::nullopt;
    home = region_[std::size_t(beside)];
  }
  Vec3 end = to;  // the point the way ends at
  if (region_[std::size_t(goal)] != home) {
    // A goal in a closed cell: the open neighbour of its cell in the start's region nearest to it, if any.
    const int inside = region_[std::size_t(goal)] < 0 ? nearest_open(goal, to, home) : -1;
    if (inside < 0) return std::nullopt;
    goal = inside;
    end = centre(goal);
    if (start == goal) return end;
  }
  // The way found last is kept while both ends stay in their cells, but not from a closed cell: where the way may
  // leave it depends on where in it the way begins.
  if (start != start_ || goal != goal_ || region_[std::size_t(start)] < 0) {
    start_ = start, goal_ = goal;
    way_.clear();
    if (++search_ == 0) {  // the stamps wrapped: forget every older search
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      search_ = 1;
    }
    const Vec3 goal_centre = centre(goal);
    // A* over the cells; the heap holds (f, cell), smallest f first and, among equal f, the smallest cell.
    heap_.clear();
    const auto later = std::greater<std::pair<double, int>>();
    auto reach = [&](int cell, double g, int from_cell) {
      if (stamp_[std::size_t(cell)] != search_) h_[std::size_t(cell)] = (centre(cell) - goal_centre).norm();
      stamp_[std::size_t(cell)] = search_;
      g_[std::size_t(cell)] = g;
      parent_[std::size_t(cell)] = from_cell;
      heap_.push_back({g + h_[std::size_t(cell)], cell});
      std::push_heap(heap_.begin(), heap_.end(), later);
    };
    reach(start, 0.0, -1);
    while (!heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), later);
      const auto [f, cell] = heap_.back();
      heap_.pop_back();
      const double g = g_[std::size_t(cell)];
      if (f > g + h_[std::size_t(cell)]) continue;  // a stale entry: reached cheaper since
      if (cell == goal) {
        for (int c = goal; c >= 0; c = parent_[std::size_t(c)]) way_.push_back(c);  // way_.back() is the start
        break;
      }
      const bool closed_start = cell == start && region_[std::size_t(start)] < 0;
      neighbours(cell, [&](int next, double step) {
        if (next != goal && region_[std::size_t(next)] < 0) return;
        // From a closed cell (next to a solid) only to the neighbours in plain sight of where the way begins.
        if (closed_start && !probe.clear(from, centre(next))) return;
        if (stamp_[std::size_t(next)] == search_ && g_[std::size_t(next)] <= g + step) return;
        reach(next, g + step, cell);
      });
    }
  }
  if (way_.empty()) return std::nullopt;
  // The farthest of the next kLookAhead cells (the goal's cell counting as `end` itself) that can be flown to straight
  // with the margin, else the farthest whose line alone is clear, else the next.
  const int last = int(way_.size()) - 2;  // the first cell after the start
  const int first = std::max(0, last - (kLookAhead - 1));
  auto point = [&](int w) { return w == 0 ? end : centre(way_[std::size_t(w)]); };
  for (int w = first; w < last; ++w) {
    if (passable(probe, from, point(w), margin)) return point(w);
  }
  for (int w = first; w <= last; ++w) {
    if (probe.clear(from, point(w))) return point(w);
  }
  // Not even the next cell in sight (a corner between): the centre of its own cell first.
  return probe.clear(from, centre(start)) ? centre(start) : point(last);
}

namespace {

// A team's pursuers ask for the same partition one after the other, each of its own roadmap of the same solids: the
// last answer on this thread is kept (one for equal speeds, one for other speeds: a pursuer may ask for both in
// turn), and given again when the grid, the sources and the speed are the same. The answer is a function of those
// alone, so keeping it changes nothing but the time.
struct LastPartition {
  Box arena;
  std::vector<int> region;
  std::vector<Vec3> sources;
  double first_speed = 1.0;
  std::vector<int> owner;
};
thread_local LastPartition last_partition[2];

}  // namespace

void Roadmap::partition(std::span<const Vec3> sources, double first_speed) {
  assert(first_speed > 0.0);
  LastPartition& last = last_partition[first_speed == 1.0 ? 0 : 1];
  if (last.arena.lo == arena_.lo && last.arena.hi == arena_.hi && last.region == region_ &&
      last.first_speed == first_speed &&
      std::equal(sources.begin(), sources.end(), last.sources.begin(), last.sources.end())) {
    owner_ = last.owner;
    return;
  }
  // Dijkstra from every source at once; g_ holds the time (the others' metres: the first source's metres over
  // first_speed), owner_ the source, and a cell's stamp says it was reached in this search.
  std::fill(owner_.begin(), owner_.end(), -1);
  if (++search_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    search_ = 1;
  }
  heap_.clear();
  const auto later = std::greater<std::pair<double, int>>();
  // A source must be strictly shorter to take a cell another reached first.
  auto reach = [&](int cell, double g, int source) {
    if (stamp_[std::size_t(cell)] == search_ && g >= g_[std::size_t(cell)]) return;
    stamp_[std::size_t(cell)] = search_;
    g_[std::size_t(cell)] = g;
    owner_[std::size_t(cell)] = source;
    heap_.push_back({g, cell});
    std::push_heap(heap_.begin(), heap_.end(), later);
  };
  const double first_pace = 1.0 / first_speed;
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const int cell = cell_of(sources[s]);
    reach(cell, (sources[s] - centre(cell)).norm() * (s == 0 ? first_pace : 1.0), int(s));
  }
  // Cells leave the heap by time. A cell of the first source's at g was reached from one taken at g - step x pace,
  // and a neighbour of one at g is decided by g + step x pace: once the heap has passed the farthest taken by the
  // longest step, no cell of the first source's is left and every neighbour of one is decided.
  const double longest = step_[26] * first_pace;
  double first_far = 0.0;  // the latest time (the others' m) of a cell of the first source's taken so far
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    const auto [g, cell] = heap_.back();
    heap_.pop_back();
    if (g > g_[std::size_t(cell)]) continue;  // a stale entry
    const int source = owner_[std::size_t(cell)];
    if (source == 0) {
      first_far = g;
    } else if (g > first_far + longest) {
      break;
    }
    const double pace = source == 0 ? first_pace : 1.0;
    neighbours(cell, [&](int next, double step) {
      if (region_[std::size_t(next)] >= 0) reach(next, g + step * pace, source);
    });
  }
  last.arena = arena_;
  last.first_speed = first_speed;
  last.region = region_;
  last.sources.assign(sources.begin(), sources.end());
  last.owner = owner_;
}

std::optional<Vec3> Roadmap::border_point(int source) const {
  // The offsets o (as in build()) to the six face neighbours: -x, +x, -y, +y, -z, +z.
  constexpr int kFaces[6] = {12, 14, 10, 16, 4, 22};
  Vec3 sum = Vec3::Zero();
  int count = 0;
  // Each face once: from a cell of the first source's to its face neighbours of `source`'s.
  auto each = [&](auto&& visit) {
    for (int c = 0; c < cells(); ++c) {
      if (owner_[std::size_t(c)] != 0) continue;
      for (const int o : kFaces) {
        const int next = c + offset_[o];
        if ((inside_[std::size_t(c)] >> o & 1u) != 0 && owner_[std::size_t(next)] == source) {
          visit(0.5 * (centre(c) + centre(next)));
        }
      }
    }
  };
  each([&](const Vec3& mid) { sum += mid, ++count; });
  if (count == 0) return std::nullopt;
  const Vec3 mean = sum / double(count);
  Vec3 best = mean;
  double nearest = std::numeric_limits<double>::infinity();
  each([&](const Vec3& mid) {
    if (const double d = (mid - mean).squaredNorm(); d < nearest) nearest = d, best = mid;
  });
  return best;
}

}  // namespace peg3d::players
