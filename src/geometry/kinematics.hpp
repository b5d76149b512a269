#pragma once
// The paper's kinematic model (eq. 1) with the sample time made explicit:
//   p(t+dt) = p(t) + v dt (sin th cos al, sin th sin al, cos th).
// The steering U = [d_alpha, d_theta] is read as a bounded change of the heading angles (docs/paper-notes.md).

#include <concepts>
#include <string>
#include <type_traits>

#include "core/config_fields.hpp"
#include "geometry/angles.hpp"
#include "geometry/vector.hpp"

namespace peg3d {

/// How the steering bound is read.
enum class SteeringReading {
  kPerStep,    ///< |d_alpha|, |d_theta| <= max_turn each sample (the paper's [-pi/4, pi/4] per step)
  kPerSecond,  ///< |d_alpha|, |d_theta| <= max_turn * dt: max_turn is a turn rate in rad/s
};

inline constexpr config::EnumNames<SteeringReading, 2> kSteeringReadingNames{
    {{SteeringReading::kPerStep, "per-step"}, {SteeringReading::kPerSecond, "per-second"}}};

/// Steering limits of one agent.
struct SteeringConfig {
  double max_turn = kPi / 4.0;  ///< rad per step (kPerStep) or rad/s (kPerSecond); (0, pi] per step
  SteeringReading reading = SteeringReading::kPerStep;
  /// rad, in [0, pi/2): theta is kept in [polar_margin, pi - polar_margin]. 0 (the paper) allows vertical
  /// flight; a margin is a climb/dive limit that keeps the heading away from the poles, where the azimuth
  /// (and every azimuth error) is undefined.
  double polar_margin = 0.0;

  /// Bound on each heading change for one sample of length dt (s), rad.
  double step_bound(double dt) const { return reading == SteeringReading::kPerStep ? max_turn : max_turn * dt; }
  /// Throws InvalidParameter naming the field, e.g. "steering.max_turn" (prefix "steering").
  void validate(const std::string& prefix = "steering") const;
  bool operator==(const SteeringConfig&) const = default;
};

/// The fields of a SteeringConfig (core/config_fields.hpp).
template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, SteeringConfig>
void visit_fields(V& v, C& c) {
  v.number("max_turn", c.max_turn, config::Range::positive(), "rad",
           "bound on each heading change: rad per step (per-step, at most pi) or rad/s (per-second); paper pi/4");
  v.choice("reading", c.reading, kSteeringReadingNames,
           "how max_turn is read: per sample (the paper's [-pi/4, pi/4]) or as a turn rate");
  v.number("polar_margin", c.polar_margin, config::Range::closed_open(0.0, kPi / 2), "rad",
           "climb/dive limit: theta stays in [margin, pi - margin]; 0 (the paper) allows vertical flight");
  v.require(c.reading != SteeringReading::kPerStep || c.max_turn <= kPi, "max_turn", c.max_turn,
            "must be <= pi when read per step");
}

/// Steering command: requested changes of the heading angles for one sample (rad).
struct Steering {
  double d_alpha = 0.0;  ///< rad, change of azimuth
  double d_theta = 0.0;  ///< rad, change of polar angle
};

/// Position and heading of one agent.
struct KinematicState {
  Vec3 position = Vec3::Zero();  ///< m
  Heading heading;
};

/// Applies a steering command: each component is clamped to [-bound, bound], theta is clamped to
/// [polar_margin, pi - polar_margin] (with margin 0 an agent can point straight up or down but not over the
/// pole) and alpha is wrapped to (-pi, pi].
Heading steer(const Heading& h, const Steering& u, double bound, double polar_margin = 0.0);

/// The motion of eq. (1) along a chosen heading: the agent takes heading h and moves speed*dt along it; the
/// new position is clamped to `bounds` (pass the arena shrunk by the agent's radius), so agents slide along
/// the arena boundary instead of leaving it.
KinematicState advance(const KinematicState& s, const Heading& h, double speed, double dt, const Box& bounds);
/// advance with the heading's direction (direction(h)) already at hand.
KinematicState advance(const KinematicState& s, const Heading& h, const Vec3& direction_of_h, double speed, double dt,
                       const Box& bounds);

/// One sample of eq. (1): the heading is steered first (steer), then the agent advances along it.
KinematicState step(const KinematicState& s, const Steering& u, double speed, double dt, double bound,
                    const Box& bounds, double polar_margin = 0.0);

}  // namespace peg3d
