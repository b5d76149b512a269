#include "sense/depth_camera.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "sense/range_reading.hpp"

namespace peg3d::sense {
namespace {

// A scan's pixel rays and what they met, and the image cast's own scratch.
struct CameraScratch final : RayScratch {
  using RayScratch::RayScratch;
  ImageCastScratch cast;
};

}  // namespace

DepthCamera::DepthCamera(const DepthCameraConfig& c) : config_(c) {
  const int w = c.enabled() ? c.width : 0, h = c.height;
  const double deg = kPi / 180.0;
  const double f = w > 0 ? 0.5 * w / std::tan(0.5 * c.hfov * deg) : 1.0;
  focal_ = f;
  // The mount: the camera's frame turned up by the elevation, then left by the azimuth, in the sensor's frame.
  const double ce = std::cos(c.mount_elevation * deg), se = std::sin(c.mount_elevation * deg);
  const double ca = std::cos(c.mount_azimuth * deg), sa = std::sin(c.mount_azimuth * deg);
  const auto mount = [&](const Vec3& v) {
    const Vec3 up(ce * v.x() - se * v.z(), v.y(), se * v.x() + ce * v.z());  // about y: x towards z
    return Vec3(ca * up.x() - sa * up.y(), sa * up.x() + ca * up.y(), up.z());  // about z: x towards y
  };
  forward_ = mount(Vec3::UnitX()), left_ = mount(Vec3::UnitY()), up_ = mount(Vec3::UnitZ());
  frame_.reserve(std::size_t(w) * std::size_t(h));
  cosine_.reserve(std::size_t(w) * std::size_t(h));
  for (int r = 0; r < h && w > 0; ++r) {
    for (int col = 0; col < w; ++col) {
      const Vec3 v(f, -(col + 0.5 - 0.5 * w), -(r + 0.5 - 0.5 * h));
      const double length = v.norm();
      frame_.push_back(mount(v / length));
      cosine_.push_back(f / length);
    }
  }
}

void DepthCamera::rays_at(const Vec3& origin, const Heading& h, std::span<Ray> out) const {
  assert(out.size() == frame_.size());
  const SensorFrame frame(h);
  for (std::size_t k = 0; k < frame_.size(); ++k) {
    out[k].origin = origin;
    out[k].direction = frame.to_world(frame_[k]);  // unit: an orthonormal frame turns a unit vector
  }
}

Pinhole DepthCamera::pinhole_at(const Heading& h) const {
  const SensorFrame frame(h);
  return {frame.to_world(forward_), -frame.to_world(left_), -frame.to_world(up_), focal_};
}

std::unique_ptr<SensorScratch> DepthCamera::make_scratch() const { return std::make_unique<CameraScratch>(frame_.size()); }

void DepthCamera::scan(const ScanContext& context, Rng& rng, ReadingOut out, SensorScratch* scratch) const {
  auto& s = static_cast<CameraScratch&>(*scratch);
  rays_at(context.eye, context.heading, s.rays);
  WorldAtInstant world = context.world;
  if (!config_.sees_agents) world.balls = {};
  const Pinhole pinhole = pinhole_at(context.heading);
  cast_image(world, s.rays, config_.width, &pinhole, config_.range, context.self, s.hits, s.cast);
  // Depth along the optical axis: each hit's distance times its pixel's cosine; noise and dropouts as the lidar's.
  read_echoes(s.hits, cosine_, {config_.range, config_.noise, config_.dropout}, rng, out.values, out.echo);
}

std::size_t DepthCamera::map_points(const Reading& reading, const SensorScratch* scratch, bool skip_agents, double beyond,
                                    std::span<Vec3> points) const {
  // An echo's depth back along its ray: the distance is the depth over the pixel's cosine.
  return ray_points(static_cast<const CameraScratch&>(*scratch), reading, cosine_, skip_agents, beyond, points);
}

void DepthCamera::segments(const SegmentContext&, std::vector<Segment>& out) const {
  out.push_back(Segment::uniform("camera.depth", pixels(), "m", 0.0, config_.range,
                                 "the depth camera's latest image: each pixel's depth along the optical axis, row-major "
                                 "from the top left (range where nothing is seen)",
                                 {config_.height, config_.width}));
}

void DepthCamera::observe(const Reading& reading, const ObserveContext&, std::span<float> out) const {
  observe_readings(reading, out);
}

nlohmann::json DepthCamera::replay(const RecordedReadings& r) const {
  return {{"hfov", config_.hfov},
          {"range", config_.range},
          {"image",
           {{"rows", config_.height},
            {"columns", config_.width},
            {"unit", "m"},
            {"low", 0.0},
            {"high", config_.range},
            {"values_f32", encoded_f32(r.values)},
            {"echo_u8", encoded_u8(r.echo)},
            {"scan_frame_u32", encoded_frames(r.scan_frames)}}}};
}

}  // namespace peg3d::sense
