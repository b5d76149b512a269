#pragma once
// A range sensor (issue 38): a lidar of azimuth_rays x elevation_rays rays over a field of view mounted on the
// agent, relative to its heading, read every `period` game steps. Each ray reads the distance to the first
// solid it meets within `range` (sense/world_rays.hpp: the map's static solids, its movers at that instant, the
// run's pushed bodies and, optionally, the other agents), with Gaussian range noise and dropouts drawn from the
// agent's own random stream. A ray that meets nothing, or drops out, reads `range` and returns no echo.
//
// The sensor's frame: x along the agent's heading, y to its left in the horizontal plane, z completing the
// right-handed frame (up for a level heading). A ray at azimuth a and elevation e in that frame points along
// (cos e cos a, cos e sin a, sin e). Rays sit at the centres of equal cells of the field of view:
//   a_i = mount_azimuth   + azimuth_fov   * ((i + 1/2) / azimuth_rays   - 1/2),  i = 0 .. azimuth_rays - 1
//   e_j = mount_elevation + elevation_fov * ((j + 1/2) / elevation_rays - 1/2),  j = 0 .. elevation_rays - 1
// and ray j * azimuth_rays + i is (a_i, e_j): rows of equal elevation, bottom row first. Rays start at the
// agent's centre (its own sphere is not seen).

#include <cstdint>
#include <span>
#include <vector>

#include "core/config_fields.hpp"
#include "core/random.hpp"
#include "geometry/angles.hpp"
#include "geometry/ray.hpp"
#include "sense/sensor.hpp"
#include "sense/static_ray_scene.hpp"

namespace peg3d::sense {

/// The most rays one lidar may have: bounds what a configuration can make a run allocate (8 bytes of range and
/// one of echo per ray and agent).
inline constexpr int kMaxLidarRays = 1 << 16;

struct LidarConfig {
  int azimuth_rays = 0;            ///< rays per row, in [0, 65536]; 0: no lidar (the default)
  int elevation_rays = 1;          ///< rows, in [1, 65536]; azimuth_rays * elevation_rays <= kMaxLidarRays
  double azimuth_fov = 360.0;      ///< deg, in (0, 360]: the span of a row's rays
  double elevation_fov = 0.0;      ///< deg, in [0, 180]: the span of the rows
  double mount_azimuth = 0.0;      ///< deg, in [-180, 180]: the field of view's centre, left of the heading
  double mount_elevation = 0.0;    ///< deg, in [-90, 90]: ... above the heading
  double range = 10.0;             ///< m, in (0, 1000]: the farthest a ray reads
  int period = 1;                  ///< game steps between scans, in [1, 1000000] (1: every step; with dt 0.1 s, 10 Hz)
  double noise = 0.0;              ///< m, >= 0: standard deviation of the Gaussian noise added to an echo's range
  double dropout = 0.0;            ///< in [0, 1]: the probability that a ray returns no echo
  bool sees_agents = true;         ///< rays meet the other agents' spheres too

  bool enabled() const { return azimuth_rays > 0; }
  int rays() const { return enabled() ? azimuth_rays * elevation_rays : 0; }
  bool operator==(const LidarConfig&) const = default;
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, LidarConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.integer("azimuth_rays", c.azimuth_rays, 0, kMaxLidarRays, "", "rays per row of the lidar; 0: no lidar (the default)");
  v.integer("elevation_rays", c.elevation_rays, 1, kMaxLidarRays, "", "rows of rays");
  v.number("azimuth_fov", c.azimuth_fov, Range::open_closed(0, 360), "deg", "horizontal span of a row's rays");
  v.number("elevation_fov", c.elevation_fov, Range::closed(0, 180), "deg", "vertical span of the rows");
  v.number("mount_azimuth", c.mount_azimuth, Range::closed(-180, 180), "deg",
           "the field of view's centre, to the left of the heading");
  v.number("mount_elevation", c.mount_elevation, Range::closed(-90, 90), "deg", "the field of view's centre, above the heading");
  v.number("range", c.range, Range::open_closed(0, 1000), "m", "the farthest a ray reads");
  v.integer("period", c.period, 1, 1000000, "steps", "game steps between scans (1: every step)");
  v.number("noise", c.noise, Range::non_negative(), "m", "standard deviation of the Gaussian noise on an echo's range");
  v.number("dropout", c.dropout, Range::closed(0, 1), "", "probability that a ray returns no echo");
  v.flag("sees_agents", c.sees_agents, "rays meet the other agents' spheres");
  v.require(static_cast<long long>(c.azimuth_rays) * c.elevation_rays <= kMaxLidarRays, "elevation_rays",
            static_cast<double>(c.elevation_rays), "makes azimuth_rays * elevation_rays more than 65536 rays");
}

/// A lidar as a sensor (sense/sensor.hpp): its rays in the sensor's frame, computed once from its configuration.
/// A reading is one range per ray (m, read_out below) and its echo; it feeds its holder's own map; its
/// observation segment is "lidar.ranges" (rays entries, m, in [0, range]); its replay layer draws its rays.
class Lidar final : public Sensor {
 public:
  explicit Lidar(const LidarConfig& config);
  const LidarConfig& config() const { return config_; }
  int rays() const { return static_cast<int>(frame_.size()); }
  /// Ray k's unit direction in the sensor's frame.
  const Vec3& frame_direction(int k) const { return frame_[std::size_t(k)]; }
  /// Writes each ray from `origin` for an agent heading `h` (world frame) into `out` (rays() long).
  void rays_at(const Vec3& origin, const Heading& h, std::span<Ray> out) const;

  std::string_view name() const override { return "lidar"; }
  int values(int) const override { return rays(); }
  int period() const override { return config_.period; }
  std::uint64_t stream() const override { return 0x6c69646172ull; }  // "lidar"
  std::unique_ptr<SensorScratch> make_scratch() const override;
  /// The rays from the eye (rays_at) against the world (sense::cast_all; the agents' balls only with
  /// sees_agents), then read_out's noise and dropouts.
  void scan(const ScanContext& context, Rng& rng, ReadingOut out, SensorScratch* scratch) const override;
  double map_range() const override { return config_.range; }
  int map_points_max() const override { return rays(); }
  std::size_t map_points(const Reading& reading, const SensorScratch* scratch, bool skip_agents, double beyond,
                         std::span<Vec3> points) const override;
  void segments(const SegmentContext& context, std::vector<Segment>& out) const override;
  void observe(const Reading& reading, const ObserveContext& context, std::span<float> out) const override;
  /// {rays, range, frame_f32 (its rays in the sensor's frame), ranges_f32 and echo_u8 (every frame's readings),
  /// scan_frame_u32 (the frame each was taken at)}.
  nlohmann::json replay(const RecordedReadings& readings) const override;

 private:
  LidarConfig config_;
  std::vector<Vec3> frame_;
};

/// A scan's readings after noise and dropout, from each ray's first hit: read_echoes (sense/range_reading.hpp) of
/// the hits' distances with the lidar's range, noise and dropout.
void read_out(const LidarConfig& config, std::span<const RayHit> hits, Rng& rng, std::span<double> ranges,
              std::span<std::uint8_t> echo);

}  // namespace peg3d::sense
