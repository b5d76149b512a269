#include "sense/lidar.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

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
