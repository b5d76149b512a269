#include "sense/lidar.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/base64.hpp"

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
  // The sensor's frame in the world: x the heading, y level and to its left, z = x cross y.
  const Vec3 x = direction(h);
  const Vec3 y(-std::sin(h.alpha), std::cos(h.alpha), 0.0);
  const Vec3 z = x.cross(y);
  for (std::size_t k = 0; k < frame_.size(); ++k) {
    const Vec3& f = frame_[k];
    out[k].origin = origin;
    out[k].direction = (f.x() * x + f.y() * y + f.z() * z).normalized();
  }
}

namespace {

// A scan's rays and what they met, exactly (before noise and dropout): what map_points reads back.
struct LidarScratch final : SensorScratch {
  std::vector<Ray> rays;
  std::vector<RayHit> hits;
};

template <class T>
std::string encoded(const std::vector<T>& values) {
  return base64(values.data(), values.size() * sizeof(T));
}

}  // namespace

std::unique_ptr<SensorScratch> Lidar::make_scratch() const {
  auto s = std::make_unique<LidarScratch>();
  s->rays.resize(frame_.size());
  s->hits.resize(frame_.size());
  return s;
}

void Lidar::scan(const ScanContext& context, Rng& rng, ReadingOut out, SensorScratch* scratch) const {
  auto& s = static_cast<LidarScratch&>(*scratch);
  rays_at(context.eye, context.heading, s.rays);
  WorldAtInstant world = context.world;
  if (!config_.sees_agents) world.balls = {};
  cast_all(world, s.rays, config_.range, context.self, s.hits);
  read_out(config_, s.hits, rng, out.values, out.echo);
}

std::size_t Lidar::map_points(const Reading& reading, const SensorScratch* scratch, bool skip_agents, double beyond,
                              std::span<Vec3> points) const {
  const auto& s = static_cast<const LidarScratch&>(*scratch);
  std::size_t n = 0;
  for (std::size_t k = 0; k < s.rays.size(); ++k) {
    if (skip_agents && s.hits[k].target == RayTarget::kBall) continue;
    points[n++] = s.rays[k].origin + (reading.echo[k] != 0 ? reading.values[k] : beyond) * s.rays[k].direction;
  }
  return n;
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
  for (std::size_t k = 0; k < reading.values.size(); ++k) out[k] = float(reading.values[k]);
}

nlohmann::json Lidar::replay(const RecordedReadings& r) const {
  std::vector<float> frame, ranges(r.values.begin(), r.values.end());
  const std::vector<std::uint8_t> echoes(r.echo.begin(), r.echo.end());
  std::vector<std::uint32_t> scan_frames;
  for (const Vec3& f : frame_) {
    for (int k = 0; k < 3; ++k) frame.push_back(float(f[k]));
  }
  for (const int f : r.scan_frames) scan_frames.push_back(std::uint32_t(std::max(0, f)));
  return {{"rays", rays()}, {"range", config_.range}, {"frame_f32", encoded(frame)}, {"ranges_f32", encoded(ranges)},
          {"echo_u8", encoded(echoes)}, {"scan_frame_u32", encoded(scan_frames)}};
}

void read_out(const LidarConfig& config, std::span<const RayHit> hits, Rng& rng, std::span<double> ranges,
              std::span<std::uint8_t> echo) {
  assert(hits.size() == ranges.size() && hits.size() == echo.size());
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const bool dropped = config.dropout > 0.0 && unit_uniform(rng) < config.dropout;
    echo[k] = hits[k].target != RayTarget::kNone && !dropped;
    double r = echo[k] != 0 ? hits[k].distance : config.range;
    if (echo[k] != 0 && config.noise > 0.0) {
      // Box-Muller from two portable uniforms (std::normal_distribution differs between standard libraries).
      const double u1 = 1.0 - unit_uniform(rng), u2 = unit_uniform(rng);
      r += config.noise * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
      r = std::clamp(r, 0.0, config.range);
    }
    ranges[k] = r;
  }
}

}  // namespace peg3d::sense
