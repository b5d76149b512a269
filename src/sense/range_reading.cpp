#include "sense/range_reading.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "core/base64.hpp"

namespace peg3d::sense {

void read_echoes(std::span<const RayHit> hits, std::span<const double> scale, const EchoNoise& n, Rng& rng,
                 std::span<double> values, std::span<std::uint8_t> echo) {
  assert(hits.size() == values.size() && hits.size() == echo.size() && (scale.empty() || scale.size() == hits.size()));
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const bool dropped = n.dropout > 0.0 && unit_uniform(rng) < n.dropout;
    echo[k] = hits[k].target != RayTarget::kNone && !dropped;
    double r = echo[k] == 0 ? n.range : scale.empty() ? hits[k].distance : hits[k].distance * scale[k];
    if (echo[k] != 0 && n.noise > 0.0) {
      // Box-Muller from two portable uniforms (std::normal_distribution differs between standard libraries).
      const double u1 = 1.0 - unit_uniform(rng), u2 = unit_uniform(rng);
      r += n.noise * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
      r = std::clamp(r, 0.0, n.range);
    }
    values[k] = r;
  }
}

std::size_t ray_points(const RayScratch& scan, const Reading& reading, std::span<const double> scale, bool skip_agents,
                       double beyond, std::span<Vec3> points) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < scan.rays.size(); ++k) {
    if (skip_agents && scan.hits[k].target == RayTarget::kBall) continue;
    const double t = reading.echo[k] == 0 ? beyond : scale.empty() ? reading.values[k] : reading.values[k] / scale[k];
    points[n++] = scan.rays[k].origin + t * scan.rays[k].direction;
  }
  return n;
}

std::string encoded_f32(std::span<const float> values) { return base64(values.data(), values.size_bytes()); }
std::string encoded_u8(std::span<const std::uint8_t> values) { return base64(values.data(), values.size_bytes()); }

std::string encoded_frames(std::span<const int> frames) {
  std::vector<std::uint32_t> out;
  out.reserve(frames.size());
  for (const int f : frames) out.push_back(std::uint32_t(std::max(0, f)));
  return base64(out.data(), out.size() * sizeof(std::uint32_t));
}

void observe_readings(const Reading& reading, std::span<float> out) {
  for (std::size_t k = 0; k < reading.values.size(); ++k) out[k] = float(reading.values[k]);
}

}  // namespace peg3d::sense
