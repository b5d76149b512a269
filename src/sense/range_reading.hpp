#pragma once
// What a range sensor (the lidar, sense/lidar.hpp; the depth camera, sense/depth_camera.hpp) makes of its rays: the
// frame it is mounted in on its holder, and its readings (noise and dropouts) from what the rays met.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/random.hpp"
#include "geometry/angles.hpp"
#include "sense/sensor.hpp"
#include "sense/world_rays.hpp"

namespace peg3d::sense {

/// A range sensor's frame on a holder heading `h`, in the world: x along the heading, y level and to its left,
/// z = x cross y (up when the heading is level). Orthonormal for every heading.
struct SensorFrame {
  Vec3 x, y, z;
  explicit SensorFrame(const Heading& h)
      : x(direction(h)), y(-std::sin(h.alpha), std::cos(h.alpha), 0.0), z(x.cross(y)) {}
  /// A vector of the sensor's frame in the world's.
  Vec3 to_world(const Vec3& v) const { return v.x() * x + v.y() * y + v.z() * z; }
};

/// The noise on a range sensor's readings.
struct EchoNoise {
  double range = 0.0;    ///< m, what a ray without an echo reads, and the clamp of a noisy one
  double noise = 0.0;    ///< m, standard deviation of the Gaussian noise on an echo
  double dropout = 0.0;  ///< probability that a ray returns no echo
};

/// A scan's readings from each ray's first hit: a ray that met a solid returns an echo unless it drops out, and
/// reads the hit's distance times scale[k] (1 when `scale` is empty) plus noise, clamped to [0, range]; without an
/// echo it reads the range. Draws from `rng` per ray, in ray order: one uniform for the dropout when dropout > 0,
/// then two uniforms (Box-Muller) for the noise of an echo when noise > 0.
void read_echoes(std::span<const RayHit> hits, std::span<const double> scale, const EchoNoise& noise, Rng& rng,
                 std::span<double> values, std::span<std::uint8_t> echo);

/// A range sensor's per-run scratch: a scan's rays and what they met, exactly (before noise and dropout), which
/// its map points are read back from.
struct RayScratch : SensorScratch {
  std::vector<Ray> rays;
  std::vector<RayHit> hits;
  explicit RayScratch(std::size_t n) : rays(n), hits(n) {}
};

/// Sensor::map_points of a range sensor whose reading k is the distance along ray k times scale[k] (1 when `scale`
/// is empty): each echo's point back along its ray, `beyond` along a ray without one, rays that met an agent left
/// out when `skip_agents`.
std::size_t ray_points(const RayScratch& scan, const Reading& reading, std::span<const double> scale, bool skip_agents,
                       double beyond, std::span<Vec3> points);

/// Sensor::observe of a range sensor: its latest readings as floats, in reading order.
void observe_readings(const Reading& reading, std::span<float> out);

/// Base64 of a recorded episode's per-frame arrays, as replay layers carry them (little-endian).
std::string encoded_f32(std::span<const float> values);
std::string encoded_u8(std::span<const std::uint8_t> values);
/// The frame each reading was taken at, as unsigned 32-bit (a frame before any reading as 0).
std::string encoded_frames(std::span<const int> frames);

}  // namespace peg3d::sense
