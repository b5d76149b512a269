#include "game/observation_vector.hpp"

namespace peg3d::game {

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
