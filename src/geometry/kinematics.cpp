#include "geometry/kinematics.hpp"

#include <algorithm>

#include "core/validation.hpp"

namespace peg3d {

void SteeringConfig::validate(const std::string& prefix) const {
  if (reading == SteeringReading::kPerStep) {
    require_in_range(prefix + ".max_turn", max_turn, 0.0, kPi, /*lo_open=*/true);
  } else {
    require_positive(prefix + ".max_turn", max_turn);
  }
}

Heading steer(const Heading& h, const Steering& u, double bound) {
  const double da = std::clamp(u.d_alpha, -bound, bound);
  const double dt = std::clamp(u.d_theta, -bound, bound);
  return {wrap_angle(h.alpha + da), std::clamp(h.theta + dt, 0.0, kPi)};
}

KinematicState step(const KinematicState& s, const Steering& u, double speed, double dt, double bound,
                    const Box& bounds) {
  KinematicState next;
  next.heading = steer(s.heading, u, bound);
  next.position = bounds.clamp(s.position + (speed * dt) * direction(next.heading));
  return next;
}

}  // namespace peg3d
