#pragma once
// A depth camera (issue 50): a pinhole image of width x height pixels, mounted on the agent like the lidar
// (sense/lidar.hpp: x along its heading, y to its left, z up), read every `period` steps. Each pixel's ray runs from
// the agent's centre through the pixel's centre and meets what a lidar's ray meets (sense/world_rays.hpp: the map's
// static solids, its movers at that instant, push mode's bodies and, optionally, the other agents), exactly in
// double precision; the pixel reads the depth of that point along the optical axis (its distance to the image
// plane through the eye, as a depth camera reports it), with Gaussian noise and dropouts drawn from the agent's own
// stream. A ray reaches `range` m; a pixel whose ray meets nothing that near, or drops out, reads `range` and has
// no echo.
//
// The image, row-major with row 0 at the top and column 0 at the left: pixel (r, c) looks along
//   (f, -(c + 1/2 - width/2), -(r + 1/2 - height/2)) in the camera's frame (x forward, y left, z up),
//   f = (width / 2) / tan(hfov / 2) pixels, square pixels (the vertical field of view follows from the aspect),
// and the camera's frame is the sensor frame turned by mount_elevation (up) and then mount_azimuth (left).
// Reading k is pixel (k / width, k % width); the observation's segment "camera.depth" has the shape (height,
// width), which Python shows as an (agents, height, width) float32 array of each game in place.

#include <cstdint>
#include <span>
#include <vector>

#include "core/config_fields.hpp"
#include "sense/image_cast.hpp"
#include "sense/sensor.hpp"

namespace peg3d::sense {

/// The most pixels one camera may have: bounds what a configuration makes a run allocate.
inline constexpr int kMaxCameraPixels = 1 << 16;

struct DepthCameraConfig {
  int width = 0;                  ///< pixels per row, in [0, 1024]; 0: no camera (the default)
  int height = 48;                ///< rows, in [1, 1024]; width * height <= kMaxCameraPixels
  double hfov = 90.0;             ///< deg, in [1, 170]: the horizontal field of view
  double range = 10.0;            ///< m, in (0, 1000]: the farthest a pixel's ray reads
  double mount_azimuth = 0.0;     ///< deg, in [-180, 180]: the optical axis, left of the heading
  double mount_elevation = 0.0;   ///< deg, in [-90, 90]: ... above the heading
  int period = 1;                 ///< game steps between images, in [1, 1000000]
  double noise = 0.0;             ///< m, >= 0: standard deviation of the Gaussian noise on an echo's depth
  double dropout = 0.0;           ///< in [0, 1]: the probability that a pixel returns no echo
  bool sees_agents = true;        ///< rays meet the other agents' spheres too

  bool enabled() const { return width > 0; }
  int pixels() const { return enabled() ? width * height : 0; }
  bool operator==(const DepthCameraConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, DepthCameraConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.integer("width", c.width, 0, 1024, "px", "pixels per row of the depth camera; 0: no camera (the default)");
  v.integer("height", c.height, 1, 1024, "px", "rows of pixels");
  v.number("hfov", c.hfov, Range::closed(1, 170), "deg", "horizontal field of view (square pixels: the vertical follows)");
  v.number("range", c.range, Range::open_closed(0, 1000), "m", "the farthest a pixel's ray reads");
  v.number("mount_azimuth", c.mount_azimuth, Range::closed(-180, 180), "deg", "the optical axis, to the left of the heading");
  v.number("mount_elevation", c.mount_elevation, Range::closed(-90, 90), "deg", "the optical axis, above the heading");
  v.integer("period", c.period, 1, 1000000, "steps", "game steps between images (1: every step)");
  v.number("noise", c.noise, Range::non_negative(), "m", "standard deviation of the Gaussian noise on an echo's depth");
  v.number("dropout", c.dropout, Range::closed(0, 1), "", "probability that a pixel returns no echo");
  v.flag("sees_agents", c.sees_agents, "rays meet the other agents' spheres");
  v.require(static_cast<long long>(c.width) * c.height <= kMaxCameraPixels, "height", static_cast<double>(c.height),
            "makes width * height more than 65536 pixels");
}

/// A depth camera under the sensor contract (sense/sensor.hpp). It feeds its holder's own map like the lidar (each
/// pixel a ray); its replay layer is an image the viewer shows for the selected agent.
class DepthCamera final : public Sensor {
 public:
  explicit DepthCamera(const DepthCameraConfig& config);
  const DepthCameraConfig& config() const { return config_; }
  int pixels() const { return static_cast<int>(frame_.size()); }
  /// Pixel k's unit ray direction in the sensor's frame (the mount applied), and the cosine of its angle to the
  /// optical axis (depth = distance along the ray x that cosine).
  const Vec3& frame_direction(int k) const { return frame_[std::size_t(k)]; }
  double axis_cosine(int k) const { return cosine_[std::size_t(k)]; }
  /// Writes each pixel's ray from `origin` for an agent heading `h` (world frame) into `out` (pixels() long).
  void rays_at(const Vec3& origin, const Heading& h, std::span<Ray> out) const;
  /// The pinhole of those rays in the world frame (sense/image_cast.hpp), for an agent heading `h`.
  Pinhole pinhole_at(const Heading& h) const;

  std::string_view name() const override { return "camera"; }
  int values(int) const override { return pixels(); }
  int period() const override { return config_.period; }
  std::uint64_t stream() const override { return 0x63616d657261ull; }  // "camera"
  std::unique_ptr<SensorScratch> make_scratch() const override;
  void scan(const ScanContext& context, Rng& rng, ReadingOut out, SensorScratch* scratch) const override;
  double map_range() const override { return config_.range; }
  int map_points_max() const override { return pixels(); }
  std::size_t map_points(const Reading& reading, const SensorScratch* scratch, bool skip_agents, double beyond,
                         std::span<Vec3> points) const override;
  void segments(const SegmentContext& context, std::vector<Segment>& out) const override;
  void observe(const Reading& reading, const ObserveContext& context, std::span<float> out) const override;
  /// {image: {rows, columns, unit "m", low 0, high range, values_f32 (every frame's depths, frame-major),
  /// echo_u8, scan_frame_u32}, hfov, range}: the viewer draws the selected agent's image.
  nlohmann::json replay(const RecordedReadings& readings) const override;

 private:
  DepthCameraConfig config_;
  std::vector<Vec3> frame_;      // per pixel, the ray in the sensor's frame
  std::vector<double> cosine_;   // per pixel, its cosine to the optical axis
  Vec3 forward_, left_, up_;     // the camera's axes in the sensor's frame (the mount applied)
  double focal_ = 1.0;           // pixels
};

}  // namespace peg3d::sense
