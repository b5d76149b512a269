#include "geometry/kinematics.hpp"

#include <algorithm>

#include "core/validation.hpp"

namespace peg3d {

void SteeringConfig::validate(const std::string& prefix) const { config::validate(*this, prefix + "."); }

Heading steer(const Heading& h, const Steering& u, double bound, double polar_margin) {
  const double da = std::clamp(u.d_alpha, -bound, bound);
  const double dt = std::clamp(u.d_theta, -bound, bound);
  return {wrap_angle(h.alpha + da), std::clamp(h.theta + dt, polar_margin, kPi - polar_margin)};
}

KinematicState advance(const KinematicState& s, const Heading& h, double speed, double dt, const Box& bounds) {
  return advance(s, h, direction(h), speed, dt, bounds);
}

KinematicState advance(const KinematicState& s, const Heading& h, const Vec3& direction_of_h, double speed, double dt,
                       const Box& bounds) {
  KinematicState next;
  next.heading = h;
  next.position = bounds.clamp(s.position + (speed * dt) * direction_of_h);
  return next;
}

KinematicState step(const KinematicState& s, const Steering& u, double speed, double dt, double bound,
                    const Box& bounds, double polar_margin) {
  return advance(s, steer(s.heading, u, bound, polar_margin), speed, dt, bounds);
}

}  // namespace peg3d
