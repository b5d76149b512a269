#include "players/search_policies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace peg3d::players {

void SearchPursuer::begin_episode(const game::AgentView& view, bool learning) {
  (void)learning;
  points_.clear();
  const Box& a = view.arena;
  const Vec3 size = a.size();
  int n[3];
  for (int k = 0; k < 3; ++k) n[k] = std::max(1, int(std::floor(size[k] / kLattice)));
  // Cell centres of an n[0] x n[1] x n[2] grid over the arena.
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k)
        points_.push_back(a.lo + Vec3((i + 0.5) * size.x() / n[0], (j + 0.5) * size.y() / n[1], (k + 0.5) * size.z() / n[2]));
  visited_.assign(points_.size(), -1.0);
  searching_ = false;
  target_ = via_ = -1;
  goal_key_ = -3;
}

void SearchPursuer::choose(const game::AgentView& view) {
  const Vec3& p = view.self.position;
  for (int round = 0; round < 2; ++round) {
    int best = -1;
    double best_cost = std::numeric_limits<double>::infinity();
    // The unknown space first: points its own map has not seen (none without a map), then any not visited.
    for (int pass = 0; pass < 2 && best < 0; ++pass) {
      for (std::size_t k = 0; k < points_.size(); ++k) {
        if (visited_[k] >= lost_at_) continue;
        if (pass == 0 && (view.probe == nullptr || view.probe->mapped(points_[k]))) continue;
        const double cost = (points_[k] - p).norm() + (points_[k] - search_from_).norm();
        if (cost < best_cost) best_cost = cost, best = int(k);
      }
    }
    if (best >= 0) {
      target_ = best;
      return;
    }
    lost_at_ = view.time;  // every point visited: a new round from here
    search_from_ = p;
  }
  target_ = -1;
}

bool SearchPursuer::passable(const game::AgentView& view, const Vec3& a, const Vec3& b) {
  return players::passable(*view.probe, a, b, kPassage);
}

bool SearchPursuer::stuck(const game::AgentView& view, int key, const Vec3& goal) {
  const double d = (goal - view.self.position).norm();
  if (key != goal_key_ || d < goal_best_ - kProgress) {
    goal_key_ = key, goal_best_ = d, goal_since_ = view.time;
    return false;
  }
  if (view.time - goal_since_ <= kStuck) return false;
  goal_since_ = view.time;  // asked again kStuck from now
  return view.probe == nullptr || !passable(view, view.self.position, goal);
}

int SearchPursuer::detour(const game::AgentView& view, const Vec3& goal) const {
  if (view.probe == nullptr) return -1;
  const Vec3& p = view.self.position;
  int best = -1;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < points_.size(); ++k) {
    const Vec3& w = points_[k];
    const double legs = (w - p).norm() + (goal - w).norm();
    if ((w - p).norm() <= kVisit || legs >= best_cost || !passable(view, p, w)) continue;
    const double cost = legs + (passable(view, w, goal) ? 0.0 : kBlockedLeg);
    if (cost < best_cost) best_cost = cost, best = int(k);
  }
  return best;
}

Steering SearchPursuer::act(const game::AgentView& view) {
  const Vec3& p = view.self.position;
  for (std::size_t k = 0; k < points_.size(); ++k) {
    if ((points_[k] - p).squaredNorm() <= kVisit * kVisit) visited_[k] = view.time;
  }
  Vec3 goal = view.other.position;
  if (view.other_visible) {
    searching_ = false;
  } else if (searching_ || (goal - p).norm() <= kArrive) {
    if (!searching_) searching_ = true, lost_at_ = view.time, search_from_ = goal, target_ = -1;
    if (target_ < 0 || visited_[std::size_t(target_)] >= lost_at_) choose(view);
    if (target_ >= 0) goal = points_[std::size_t(target_)];
  }
  if (via_ >= 0 && (visited_[std::size_t(via_)] == view.time || stuck(view, 10000 + via_, points_[std::size_t(via_)]))) {
    via_ = -1;
  }
  if (via_ < 0 && stuck(view, view.other_visible || !searching_ ? -2 : target_, goal)) {
    via_ = detour(view, goal);
    if (via_ < 0 && !view.other_visible) {
      if (searching_ && target_ >= 0) {
        visited_[std::size_t(target_)] = view.time;  // unreachable from here: the next one
      } else if (!searching_) {
        searching_ = true, lost_at_ = view.time, search_from_ = goal, target_ = -1;  // as if arrived
      }
    }
  }
  if (via_ >= 0) goal = points_[std::size_t(via_)];
  return steer_toward(view, goal - p);
}

void HideEvader::begin_episode(const game::AgentView& view, bool learning) {
  (void)view;
  (void)learning;
  has_spot_ = false;
}

bool HideEvader::find_cover(const game::AgentView& view) {
  const Vec3& e = view.self.position;
  const Vec3& p = view.other.position;
  const Box inside = view.arena.shrunk(kHideMargin);
  const double from_pursuer = (e - p).norm();
  double best = std::numeric_limits<double>::infinity();
  for (int a = 0; a < kHideAzimuths; ++a) {
    const double az = 2.0 * kPi * a / kHideAzimuths;
    for (const double el_deg : {0.0, -30.0, 30.0}) {
      const double el = el_deg * kPi / 180.0;
      const Vec3 d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
      for (const double r : kHideDistances) {
        const Vec3 h = e + r * d;
        if (!inside.contains(h)) continue;
        const double cost = r - 0.5 * ((h - p).norm() - from_pursuer);
        if (cost >= best) continue;
        if (!view.probe->clear(e, h) || view.probe->clear(p, h)) continue;
        best = cost;
        spot_ = h;
      }
    }
  }
  return best < std::numeric_limits<double>::infinity();
}

Steering HideEvader::act(const game::AgentView& view) {
  const Vec3& e = view.self.position;
  const Vec3& p = view.other.position;
  if (view.probe == nullptr) return flee_.act(view);
  if (has_spot_ && view.probe->clear(p, spot_)) has_spot_ = false;  // the pursuer would see it there now
  if (!has_spot_ && (view.other_visible || view.other_age < kAlert)) has_spot_ = find_cover(view);
  if (has_spot_) return steer_toward(view, spot_ - e);
  return flee_.act(view);
}

}  // namespace peg3d::players
