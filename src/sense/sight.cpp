#include "sense/sight.hpp"

#include <cmath>

#include "core/step_profile.hpp"
#include "sense/line_of_sight.hpp"

namespace peg3d::sense {

bool in_sight(const WorldAtInstant& world, const SightConfig& c, const Vec3& self, const Heading& heading,
              const Vec3& centre, double radius) {
  const Vec3 line = centre - self;
  const double d2 = line.squaredNorm();
  if (d2 > c.range * c.range) return false;
  if (c.fov < 360.0 && d2 > 0.0) {
    // Within the cone: the angle to the heading at most fov / 2, compared as cosines.
    const double cos_half = std::cos(0.5 * c.fov * kPi / 180.0);
    if (direction(heading).dot(line) < cos_half * std::sqrt(d2)) return false;
  }
  return line_of_sight(world, self, centre, radius, c.points);
}

void SightSensor::scan(const ScanContext& context, Rng&, ReadingOut out, SensorScratch*) const {
  const StepProfile::Scope profiled(StepProfile::kSight);
  WorldAtInstant world = context.world;
  world.balls = {};  // other agents do not hide an opponent
  for (std::size_t j = 0; j < out.values.size(); ++j) {
    const bool target = j < context.targets.size() && context.targets[j] != 0;
    const Ball& b = context.world.balls[j];
    out.echo[j] = target && in_sight(world, config_, context.eye, context.heading, b.centre, b.radius);
    out.values[j] = out.echo[j];
  }
}

void SightSensor::segments(const SegmentContext& context, std::vector<Segment>& out) const {
  out.push_back(Segment::uniform("sight.visible", 1, "", 0.0, 1.0,
                                 "1 while the opponent of the first entries is in sight now (always 1 with full information)"));
  out.push_back(Segment::uniform("sight.age", 1, "s", 0.0, context.time_limit,
                                 "how old the sighting the first entries come from is (0 while in sight)"));
}

void SightSensor::observe(const Reading&, const ObserveContext& context, std::span<float> out) const {
  out[0] = context.opponent_visible ? 1.0f : 0.0f;
  out[1] = float(context.opponent_age);
}

nlohmann::json SightSensor::replay(const RecordedReadings&) const {
  return {{"fov", config_.fov}, {"range", config_.range}};
}

}  // namespace peg3d::sense
