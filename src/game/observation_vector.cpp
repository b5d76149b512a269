#include "game/observation_vector.hpp"

namespace peg3d::game {

std::pair<double, double> entry_bounds(EntryRange range, const Box& box, double reach, double speed) {
  const Vec3 extent = box.hi - box.lo;
  switch (range) {
    case EntryRange::kDistance: return {0.0, reach};
    case EntryRange::kAngle: return {-kPi, kPi};
    case EntryRange::kPolar: return {0.0, kPi};
    case EntryRange::kPositionX: return {box.lo.x(), box.hi.x()};
    case EntryRange::kPositionY: return {box.lo.y(), box.hi.y()};
    case EntryRange::kPositionZ: return {box.lo.z(), box.hi.z()};
    case EntryRange::kOffsetX: return {-extent.x(), extent.x()};
    case EntryRange::kOffsetY: return {-extent.y(), extent.y()};
    case EntryRange::kOffsetZ: return {-extent.z(), extent.z()};
    case EntryRange::kVelocity: return {-speed, speed};
    case EntryRange::kReach: return {-reach, reach};
  }
  return {0.0, 0.0};
}

void observation_base(const AgentView& v, float* o) {
  const Percept& p = v.percept;
  const Vec3& self = v.self.position;
  const Vec3 rel = v.other.position - self;
  const Vec3 vel = v.other_speed * direction(v.other.heading);
  const Vec3 obstacle = v.field.found ? Vec3(v.field.point - self) : Vec3::Zero();
  const double x[kObservationBase] = {
      p.target_distance,  p.target.azimuth,    p.target.elevation, p.obstacle.distance, p.to_obstacle.azimuth,
      p.to_obstacle.elevation, self.x(),       self.y(),           self.z(),            v.self.heading.alpha,
      v.self.heading.theta, rel.x(),           rel.y(),            rel.z(),             vel.x(),
      vel.y(),            vel.z(),             obstacle.x(),       obstacle.y(),        obstacle.z()};
  for (int k = 0; k < kObservationBase; ++k) o[k] = static_cast<float>(x[k]);
}

}  // namespace peg3d::game
