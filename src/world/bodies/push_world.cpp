#include "world/bodies/push_world.hpp"

#include <algorithm>
#include <cmath>
#include <cassert>
#include <limits>


namespace peg3d::world {

PushWorld::PushWorld(const MapSpec& spec, std::shared_ptr<const StaticPhysicsShapes> statics, int substeps)
    : spec_(spec),
      physics_(std::make_unique<BodyPhysics>(spec, std::move(statics), spec.movers, true)),
      substeps_(substeps),
      h_(1.0 / spec.physics.rate_hz) {
  // The sensor can overlap at most every dynamic body: sized once, no step allocates.
  std::size_t dynamic = 0;
  for (const MoverSpec& m : spec_.movers) dynamic += !m.kinematic();
  near_.resize(std::max<std::size_t>(1, dynamic));
  candidates_.reserve(dynamic);
}

void PushWorld::add_agent(double radius, const Vec3& at) {
  physics_->add_agent(radius, at, kSensorReach);
  radius_.push_back(radius);
  in_world_.push_back(true);
  stopped_.push_back(false);
  pushed_.reserve(in_world_.size() * near_.size());
}

void PushWorld::remove_agent(int i) {
  if (!in_world_[std::size_t(i)]) return;
  physics_->remove_agent(i);
  in_world_[std::size_t(i)] = false;
}

void PushWorld::advance(std::span<const Vec3> from, std::span<Vec3> to, std::vector<Contact>& touches) {
  const int n = static_cast<int>(radius_.size());
  assert(static_cast<int>(from.size()) == n && static_cast<int>(to.size()) == n);
  const std::size_t first_touch = touches.size();
  pushed_.clear();
  for (int i = 0; i < n; ++i) stopped_[std::size_t(i)] = false;
  const int movers = static_cast<int>(spec_.movers.size());
  for (int j = 1; j <= substeps_; ++j) {
    const double s = static_cast<double>(j) / substeps_;
    for (int i = 0; i < n; ++i) {
      if (!in_world_[std::size_t(i)] || stopped_[std::size_t(i)]) continue;
      physics_->move_agent(i, from[std::size_t(i)] + s * (to[std::size_t(i)] - from[std::size_t(i)]));
    }
    ++substep_;
    physics_->step(static_cast<double>(substep_) * h_, h_);
    for (int i = 0; i < n; ++i) {
      if (!in_world_[std::size_t(i)] || stopped_[std::size_t(i)]) continue;
      const int count = physics_->bodies_near_agent(i, near_);
      assert(count <= static_cast<int>(near_.size()));
      const Vec3 c = from[std::size_t(i)] + s * (to[std::size_t(i)] - from[std::size_t(i)]);
      // Bullet's contacts act a substep ahead (the solver lets a gap close by no more than it is): a body within
      // the agent's travel of a substep is touched.
      const double reach = kTouchTolerance + (to[std::size_t(i)] - from[std::size_t(i)]).norm() / substeps_;
      for (int q = 0; q < count; ++q) {
        const int m = near_[std::size_t(q)];
        const MoverSpec& spec = spec_.movers[std::size_t(m)];
        const Pose at = physics_->pose(std::size_t(m));
        const double gap = signed_distance(spec.shape, at, c) - radius_[std::size_t(i)];
        if (gap > reach) continue;
        const bool solid = spec.dynamic.touch == DynamicMotion::Touch::kSolid;
        if (!solid) {
          const int key = i * movers + m;
          if (std::find(pushed_.begin(), pushed_.end(), key) != pushed_.end()) continue;
          pushed_.push_back(key);
        }
        const TouchPoint tp = touch_point(spec.shape, at, c, radius_[std::size_t(i)]);
        Contact touch;
        touch.agent = i;
        touch.kind = ObstacleKind::kMover;
        touch.obstacle_id = m;
        touch.fraction = s;
        touch.point = tp.point;
        touch.normal = tp.normal;
        touch.penetration = std::max(0.0, -gap);
        touch.pushed = !solid;
        touches.push_back(touch);
        if (solid) {
          // It stops where it stood a substep earlier, apart from the body, and stays there for the step.
          const double back = static_cast<double>(j - 1) / substeps_;
          to[std::size_t(i)] = from[std::size_t(i)] + back * (to[std::size_t(i)] - from[std::size_t(i)]);
          physics_->move_agent(i, to[std::size_t(i)]);
          stopped_[std::size_t(i)] = true;
          break;
        }
      }
    }
  }
  // Agents in index order, each in time order (found substep by substep, agent by agent): a stable insertion
  // sort, as std::stable_sort may allocate its buffer and a step allocates nothing.
  for (std::size_t k = first_touch + 1; k < touches.size(); ++k) {
    for (std::size_t j = k; j > first_touch && touches[j - 1].agent > touches[j].agent; --j) std::swap(touches[j - 1], touches[j]);
  }
}

MoverPoint PushWorld::nearest(const Vec3& p, double cap) const {
  MoverPoint best;
  best.distance = cap;
  candidates_.clear();
  const Box box = std::isfinite(cap) ? Box{p.array() - cap, p.array() + cap} : spec_.bounds;
  physics_->bodies_in(box, candidates_);
  for (const int m : candidates_) {
    const Shape& shape = spec_.movers[std::size_t(m)].shape;
    offer_nearer(m, shape, shape.bounding_radius(), physics_->pose(std::size_t(m)), p, best);
  }
  return best;
}

Pose PushWorld::pose(int m) const { return physics_->pose(std::size_t(m)); }

}  // namespace peg3d::world
