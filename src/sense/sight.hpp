#pragma once
// The sight sensor (issue 39, docs/sight.md): opponents seen only in line of sight. Its settings, and the test
// itself (sense/line_of_sight.hpp) as a detector under the sensor contract (sense/sensor.hpp): a reading says which
// agents it sees now. What its holder does with what it sees (its memory of sightings, their estimates, the
// sharing between teammates) is the game's knowledge of its opponents (game/knowledge.hpp), which the detection()
// settings steer.

#include <concepts>
#include <type_traits>

#include "core/config_fields.hpp"
#include "sense/sensor.hpp"

namespace peg3d::sense {


/// Opponents seen only in line of sight (issue 39, docs/sight.md). Off (the default): the agent knows every
/// opponent's state at every step, the paper's full information. On: after each step (and at the reset) the
/// agent looks at every opponent in the game; it sees one when the opponent's centre is within `range`, within
/// the field of view (the angle between the agent's heading and the line to that centre is at most fov / 2),
/// and a sight ray reaches the opponent's sphere before any terrain, obstacle or mover (sense/line_of_sight.hpp:
/// `points` rays; other agents do not hide it). Each agent remembers its latest sighting of each opponent
/// (position, heading, velocity, when); every agent starts knowing where each opponent starts. Its opponent
/// inputs (the percept, the motion space, the Python entries) come from the estimate built on that sighting;
/// its rewards still measure the true distance.
struct SightConfig {
  bool enabled = false;  ///< limited sight; false: full information (the default)
  double range = 100.0;  ///< m, in (0, 1000]: the farthest an opponent's centre can be seen
  double fov = 360.0;    ///< deg, in (0, 360]: the field of view's full angle about the heading (360: all round)
  int points = 5;        ///< sight rays per look at an opponent, in [1, 9]: its centre, then points of its rim
  SightEstimate estimate = SightEstimate::kLastSeen;  ///< what the inputs hold while the opponent is out of sight
  /// Teammates share sightings: every agent of the role with share on holds the newest sighting any of them
  /// has of each opponent, and sees what any of them sees.
  bool share = false;
  bool operator==(const SightConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, SightConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.flag("enabled", c.enabled, "opponents are seen only in line of sight (false: full information, the default)");
  v.number("range", c.range, Range::open_closed(0, 1000), "m", "the farthest an opponent's centre can be seen");
  v.number("fov", c.fov, Range::open_closed(0, 360), "deg",
           "the field of view's full angle about the heading, a cone (360: all round)");
  v.integer("points", c.points, 1, 9, "", "sight rays per look at an opponent: its centre, then points of its rim");
  v.choice("estimate", c.estimate, kSightEstimateNames,
           "an opponent out of sight is where it was last seen, or moved on at its velocity then (dead-reckoning)");
  v.flag("share", c.share, "teammates with share on pool their sightings");
}

/// The sight test as a detector: a reading holds, per agent of the game, 1 when the holder sees it now (echo 1)
/// and 0 otherwise; it looks only at its targets (the holder's opponents in the game). It sees an agent when the
/// agent's centre lies within `range` and the field of view and a sight ray reaches its sphere before any solid
/// (sense/line_of_sight.hpp; other agents do not hide it). Its observation segments are the knowledge it gives:
/// "sight.visible" (1 while the opponent of the observation's first entries is in sight) and "sight.age" (s, how
/// old the sighting those entries come from is).
class SightSensor final : public Sensor {
 public:
  explicit SightSensor(const SightConfig& config) : config_(config), detection_{config.estimate, config.share} {}
  const SightConfig& config() const { return config_; }

  std::string_view name() const override { return "sight"; }
  int values(int agents) const override { return agents; }
  void scan(const ScanContext& context, Rng& rng, ReadingOut out, SensorScratch* scratch) const override;
  const Detection* detection() const override { return &detection_; }
  void segments(const SegmentContext& context, std::vector<Segment>& out) const override;
  void observe(const Reading& reading, const ObserveContext& context, std::span<float> out) const override;
  /// {fov (deg), range (m)}; the game's knowledge adds what the holder took its opponent to be, frame by frame.
  nlohmann::json replay(const RecordedReadings& readings) const override;

 private:
  SightConfig config_;
  Detection detection_;
};

/// Whether an eye at `self` (centre) heading `heading`, with sight `config`, sees the sphere (centre, radius) in
/// `world` (its balls ignored): within range and field of view, and a sight ray reaching it.
bool in_sight(const WorldAtInstant& world, const SightConfig& config, const Vec3& self, const Heading& heading,
              const Vec3& centre, double radius);

}  // namespace peg3d::sense
