#include "sense/line_of_sight.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "geometry/angles.hpp"

namespace peg3d::sense {

void sight_points(const Vec3& eye, const Vec3& c, double r, int n, std::span<Vec3> out) {
  assert(n >= 1 && n <= kMaxSightPoints && out.size() >= std::size_t(n));
  out[0] = c;
  if (n == 1) return;
  const Vec3 line = c - eye;
  const double length = line.norm();
  // The first rim point towards world up (its part perpendicular to the line), +x for a vertical line.
  const auto [up, side] = perpendicular_frame(length > 0.0 ? Vec3(line / length) : Vec3::UnitZ());
  const double rim = kRimFraction * r;
  for (int k = 1; k < n; ++k) {
    const double a = 2.0 * kPi * double(k - 1) / double(n - 1);
    out[std::size_t(k)] = c + rim * (std::cos(a) * up + std::sin(a) * side);
  }
}

namespace {

// Casts `count` rays (eye -> points[k]) and says whether one of them enters the sphere before any solid.
bool any_reaches(const WorldAtInstant& world, const Vec3& eye, const Vec3& c, double r, const Vec3* points, int count) {
  std::array<Ray, kMaxSightPoints> rays;
  std::array<double, kMaxSightPoints> entry;
  std::array<RayHit, kMaxSightPoints> hits;
  double range = 0.0;
  for (int k = 0; k < count; ++k) {
    const Vec3 to = points[k] - eye;
    const double length = to.norm();
    rays[std::size_t(k)] = {eye, to / length};
    // Where the ray enters the sphere: it aims inside it, so it does within `length`.
    const auto in = ray_sphere(rays[std::size_t(k)], c, r, length);
    entry[std::size_t(k)] = in ? *in : length;
    range = std::max(range, entry[std::size_t(k)]);
  }
  WorldAtInstant solids = world;
  solids.balls = {};
  cast_all(solids, {rays.data(), std::size_t(count)}, range, -1, {hits.data(), std::size_t(count)});
  for (int k = 0; k < count; ++k) {
    const RayHit& h = hits[std::size_t(k)];
    if (h.target == RayTarget::kNone || h.distance >= entry[std::size_t(k)]) return true;
  }
  return false;
}

}  // namespace

bool line_of_sight(const WorldAtInstant& world, const Vec3& eye, const Vec3& c, double r, int points) {
  assert(points >= 1 && points <= kMaxSightPoints);
  if ((c - eye).squaredNorm() <= r * r) return true;
  std::array<Vec3, kMaxSightPoints> at;
  sight_points(eye, c, r, points, at);
  if (any_reaches(world, eye, c, r, at.data(), 1)) return true;
  return points > 1 && any_reaches(world, eye, c, r, at.data() + 1, points - 1);
}

}  // namespace peg3d::sense
