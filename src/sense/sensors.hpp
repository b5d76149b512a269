#pragma once
// The sensors an agent can carry (issue 50): their settings, one section each of the agent's configuration
// (game/agent_config.hpp embeds them: "sight", "lidar", ...), and the list of sensors the settings turn on. Adding
// a sensor: its class under the contract of sense/sensor.hpp, its settings here, one line in make_sensors
// (docs/architecture.md, "Adding a sensor"); nothing outside sense/ names it.

#include <concepts>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/config_fields.hpp"
#include "sense/depth_camera.hpp"
#include "sense/lidar.hpp"
#include "sense/sensor.hpp"
#include "sense/sight.hpp"

namespace peg3d::sense {

/// Every sensor's settings; a sensor is off unless its settings turn it on.
struct SensorSettings {
  SightConfig sight;  ///< opponents seen only in line of sight (off by default: full information)
  LidarConfig lidar;  ///< a range sensor (none by default)
  DepthCameraConfig camera;  ///< a depth camera (none by default)
  bool operator==(const SensorSettings&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, SensorSettings>
void visit_fields(V& v, C& c) {
  v.section("sight", c.sight, "opponents seen only in line of sight (docs/sight.md); off by default");
  v.section("lidar", c.lidar, "the agent's range sensor (sense/lidar.hpp); none by default");
  v.section("camera", c.camera, "the agent's depth camera (sense/depth_camera.hpp); none by default");
}

/// The sensors `settings` turn on, in the order an agent carries them and its observation lists their segments:
/// sight, the lidar, then the depth camera.
std::vector<std::unique_ptr<const Sensor>> make_sensors(const SensorSettings& settings);

/// Whether some sensor of `settings` feeds its holder's own map (map_range() > 0).
bool feeds_map(const SensorSettings& settings);
/// What a configuration turns on for feeds_map() to hold, as messages say it.
inline constexpr const char* kMapFeeders =
    "needs a sensor whose scans feed it: a lidar (lidar.azimuth_rays > 0) or a depth camera (camera.width > 0)";

}  // namespace peg3d::sense
