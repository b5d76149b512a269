#pragma once
// What a sensor is (issue 50): one interface that the game steps every sensor through, so that the game knows
// none by name. A Sensor is built once per agent configuration from its settings (sense/sensors.hpp) and is
// read-only, shared by every run and thread; what changes in a run (its readings, its random stream, its scratch)
// lives in the run's state. Its contract, in the order a run uses it:
//
//   values(agents)     how many numbers one reading holds (rays, pixels; one per agent for a detector)
//   period()           game steps between readings (it reads at the reset and at every step it divides)
//   stream()           the tag of its random stream among those derived from the reset's seed
//   make_scratch()     its own per-run scratch, made once per state (none by default)
//   scan(...)          reads the world at an instant from the holder's eye into a Reading: values and echoes
//   map_points(...)    what a scan adds to the holder's own map (sense/scan_map.hpp): its rays' endpoints
//   detection()        a sensor that detects agents (the sight test): the holder knows an opponent only
//                      through its detections (game/knowledge.hpp keeps the memory of them)
//   segments(...)      its part of the holder's observation vector: named segments with units and bounds
//   observe(...)       writes those entries from its latest reading and the holder's view
//   replay(...)        its layer of the browser replay (view/replay.cpp), from the readings a trace recorded
//
// A reading's numbers are doubles (m for ranges and depths); the trace and the journal keep them as floats,
// which is what observations and replays show.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/config_fields.hpp"
#include "core/random.hpp"
#include "geometry/angles.hpp"
#include "sense/segment.hpp"
#include "sense/world_rays.hpp"

namespace peg3d::sense {

/// The holder of a sensor at the instant of a scan, and what the world holds then.
struct ScanContext {
  /// What rays meet now: the map's static solids, its movers, push mode's bodies, and `world.balls`, every agent
  /// (radius 0 for one out of the game). A sensor that does not see agents leaves the balls out.
  WorldAtInstant world;
  Vec3 eye = Vec3::Zero();  ///< m, the holder's centre
  Heading heading;          ///< the holder's heading
  int self = -1;            ///< the holder's index among the balls (its own sphere is not seen)
  /// Per ball, 1 for an agent a detector looks for now: the holder's opponents in the game (empty: none).
  std::span<const std::uint8_t> targets;
};

class Sensor;

/// One reading of a sensor: its numbers and, per number, whether it is an echo (a ray that met a solid; for a
/// detector, an agent seen). Spans into the run's state; `step` is the step it was taken at (0: the reset's; -1:
/// none yet); `sensor` the sensor that took it.
struct Reading {
  std::span<const double> values;
  std::span<const std::uint8_t> echo;
  int step = -1;
  const Sensor* sensor = nullptr;
};

/// Writable storage for one scan.
struct ReadingOut {
  std::span<double> values;
  std::span<std::uint8_t> echo;
};

/// What an agent with limited sight estimates an opponent it does not see now to be doing (SightConfig::estimate).
enum class SightEstimate {
  kLastSeen,       ///< where it was last seen, heading as it was
  kDeadReckoning,  ///< where it was last seen, moved on since at the velocity it had then (kept in the arena)
};
inline constexpr config::EnumNames<SightEstimate, 2> kSightEstimateNames{
    {{SightEstimate::kLastSeen, "last-seen"}, {SightEstimate::kDeadReckoning, "dead-reckoning"}}};

/// What a detector (a sensor whose echoes say which agents it sees) tells the game about its holder's knowledge of
/// its opponents (docs/sight.md).
struct Detection {
  SightEstimate estimate = SightEstimate::kLastSeen;  ///< what the holder takes an unseen opponent to be doing
  bool share = false;                                 ///< the holder pools its sightings with teammates that share
};

/// What a sensor's segments depend on besides its own settings.
struct SegmentContext {
  double time_limit = 0.0;  ///< s, an episode's length
};

/// What observe() reads besides the sensor's latest reading: the holder's knowledge of the opponent of its
/// observation's first entries (game::AgentView's other_visible and other_age).
struct ObserveContext {
  bool opponent_visible = true;  ///< the opponent is in sight now (always with full information)
  double opponent_age = 0.0;     ///< s, how old the sighting the first entries come from is
};

/// One sensor's readings over a recorded episode, as a trace keeps them (game/episode.hpp): `frames` frames of
/// `size` values each, frame-major, their echoes, and per frame the frame its reading was taken at.
struct RecordedReadings {
  int frames = 0;
  int size = 0;
  std::span<const float> values;
  std::span<const std::uint8_t> echo;
  std::span<const int> scan_frames;
};

/// A sensor's own per-run scratch (buffers a scan reuses); each state makes one per sensor it carries.
class SensorScratch {
 public:
  virtual ~SensorScratch() = default;
};

class Sensor {
 public:
  virtual ~Sensor() = default;

  /// Its settings section in the agent's configuration ("lidar", "camera", "sight"): it names its observation
  /// segments ("lidar.ranges") and its replay layer.
  virtual std::string_view name() const = 0;
  /// Numbers one reading holds in a game of `agents` agents.
  virtual int values(int agents) const = 0;
  /// Game steps between readings, >= 1.
  virtual int period() const { return 1; }
  /// The tag of its random stream: derive_seed(reset seed, {stream(), agent index}). 0: it draws nothing.
  virtual std::uint64_t stream() const { return 0; }
  /// Its per-run scratch; null when it needs none.
  virtual std::unique_ptr<SensorScratch> make_scratch() const { return nullptr; }

  /// Reads the world now into `out` (values(agents) long), drawing any noise from `rng`; `scratch` is what
  /// make_scratch() made (null when it made none). No allocation once the scratch has seen a scan.
  virtual void scan(const ScanContext& context, Rng& rng, ReadingOut out, SensorScratch* scratch) const = 0;

  /// The range (m) its points go into the holder's own map with (insertPointCloud's max_range); 0: it feeds no map.
  virtual double map_range() const { return 0.0; }
  /// The most points map_points() writes for one scan.
  virtual int map_points_max() const { return 0; }
  /// The points its latest scan (`reading`, and the scratch that scan used) adds to the holder's own map, as
  /// OctoMap's insertPointCloud takes them: an echo's endpoint, or for a ray without one the point `beyond` (m)
  /// along it, which carves free space only. `skip_agents`: leave out the rays that met an agent. Writes them to
  /// `points` (map_points_max() long) and returns how many.
  virtual std::size_t map_points(const Reading& reading, const SensorScratch* scratch, bool skip_agents, double beyond,
                                 std::span<Vec3> points) const {
    (void)reading, (void)scratch, (void)skip_agents, (void)beyond, (void)points;
    return 0;
  }
  /// Non-null for a detector: see Detection.
  virtual const Detection* detection() const { return nullptr; }

  /// Its segments of the holder's observation, appended in order (offsets are the table's to set).
  virtual void segments(const SegmentContext& context, std::vector<Segment>& out) const {
    (void)context, (void)out;
  }
  /// Writes its entries of the observation (as many as its segments hold, in their order) from its latest
  /// reading.
  virtual void observe(const Reading& reading, const ObserveContext& context, std::span<float> out) const {
    (void)reading, (void)context, (void)out;
  }

  /// Its layer of a replay (view/replay.cpp): what the viewer draws of it, as a JSON object; null when it has none.
  virtual nlohmann::json replay(const RecordedReadings& readings) const {
    (void)readings;
    return nullptr;
  }
};

}  // namespace peg3d::sense
