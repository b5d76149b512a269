#include "sense/sensors.hpp"

namespace peg3d::sense {

std::vector<std::unique_ptr<const Sensor>> make_sensors(const SensorSettings& s) {
  std::vector<std::unique_ptr<const Sensor>> out;
  if (s.sight.enabled) out.push_back(std::make_unique<SightSensor>(s.sight));
  if (s.lidar.enabled()) out.push_back(std::make_unique<Lidar>(s.lidar));
  if (s.camera.enabled()) out.push_back(std::make_unique<DepthCamera>(s.camera));
  return out;
}

bool feeds_map(const SensorSettings& s) {
  for (const auto& sensor : make_sensors(s)) {
    if (sensor->map_range() > 0.0) return true;
  }
  return false;
}

}  // namespace peg3d::sense
