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
  require_in_range(prefix + ".polar_margin", polar_margin, 0.0, kPi / 2, false, /*hi_open=*/true);
}

Heading steer(const Heading& h, const Steering& u, double bound, double polar_margin) {
  const double da = std::clamp(u.d_alpha, -bound, bound);
  const double dt = std::clamp(u.d_theta, -bound, bound);
  return {wrap_angle(h.alpha + da), std::clamp(h.theta + dt, polar_margin, kPi - polar_margin)};
}

KinematicState step(const KinematicState& s, const Steering& u, double speed, double dt, double bound,
                    const Box& bounds, double polar_margin) {
  KinematicState next;
  next.heading = steer(s.heading, u, bound, polar_margin);
  next.position = bounds.clamp(s.position + (speed * dt) * direction(next.heading));
  return next;
}

}  // namespace peg3d
