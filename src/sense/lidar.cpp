#include "sense/lidar.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "sense/range_reading.hpp"


namespace peg3d::sense {

Lidar::Lidar(const LidarConfig& config) : config_(config) {
  const int na = config.enabled() ? config.azimuth_rays : 0, ne = config.elevation_rays;
  frame_.reserve(std::size_t(na) * std::size_t(ne));
  const double deg = kPi / 180.0;
  for (int j = 0; j < ne && na > 0; ++j) {
    const double e = deg * (config.mount_elevation + config.elevation_fov * ((j + 0.5) / ne - 0.5));
    for (int i = 0; i < na; ++i) {
      const double a = deg * (config.mount_azimuth + config.azimuth_fov * ((i + 0.5) / na - 0.5));
      frame_.emplace_back(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    }
  }
}

void Lidar::rays_at(const Vec3& origin, const Heading& h, std::span<Ray> out) const {
  assert(out.size() == frame_.size());
  const SensorFrame frame(h);
  for (std::size_t k = 0; k < frame_.size(); ++k) {
    out[k].origin = origin;
    out[k].direction = frame.to_world(frame_[k]).normalized();
  }
}

std::unique_ptr<SensorScratch> Lidar::make_scratch() const { return std::make_unique<RayScratch>(frame_.size()); }

void Lidar::scan(const ScanContext& context, Rng& rng, ReadingOut out, SensorScratch* scratch) const {
  auto& s = static_cast<RayScratch&>(*scratch);
  rays_at(context.eye, context.heading, s.rays);
  WorldAtInstant world = context.world;
  if (!config_.sees_agents) world.balls = {};
  cast_all(world, s.rays, config_.range, context.self, s.hits);
  read_out(config_, s.hits, rng, out.values, out.echo);
}

std::size_t Lidar::map_points(const Reading& reading, const SensorScratch* scratch, bool skip_agents, double beyond,
                              std::span<Vec3> points) const {
  return ray_points(static_cast<const RayScratch&>(*scratch), reading, {}, skip_agents, beyond, points);
}

void Lidar::segments(const SegmentContext&, std::vector<Segment>& out) const {
  const int n = rays();
  std::vector<int> shape = config_.elevation_rays > 1 ? std::vector<int>{config_.elevation_rays, config_.azimuth_rays}
                                                      : std::vector<int>{n};
  out.push_back(Segment::uniform("lidar.ranges", n, "m", 0.0, config_.range,
                                 "the lidar's latest range per ray, rows of equal elevation, bottom row first",
                                 std::move(shape)));
}

void Lidar::observe(const Reading& reading, const ObserveContext&, std::span<float> out) const {
  observe_readings(reading, out);
}

nlohmann::json Lidar::replay(const RecordedReadings& r) const {
  std::vector<float> frame;
  for (const Vec3& f : frame_) {
    for (int k = 0; k < 3; ++k) frame.push_back(float(f[k]));
  }
  return {{"rays", rays()},
          {"range", config_.range},
          {"frame_f32", encoded_f32(frame)},
          {"ranges_f32", encoded_f32(r.values)},
          {"echo_u8", encoded_u8(r.echo)},
          {"scan_frame_u32", encoded_frames(r.scan_frames)}};
}

void read_out(const LidarConfig& config, std::span<const RayHit> hits, Rng& rng, std::span<double> ranges,
              std::span<std::uint8_t> echo) {
  read_echoes(hits, {}, {config.range, config.noise, config.dropout}, rng, ranges, echo);
}

}  // namespace peg3d::sense
