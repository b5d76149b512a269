#include "world/map/movers.hpp"

#include <cmath>

#include <fmt/format.h>

#include "geometry/angles.hpp"

namespace peg3d::world {

const char* to_string(MoverSpec::Motion m) {
  switch (m) {
    case MoverSpec::Motion::kPath: return "path";
    case MoverSpec::Motion::kOrbit: return "orbit";
    case MoverSpec::Motion::kDynamic: return "dynamic";
  }
  return "?";
}

Quat orientation_deg(const Vec3& r) {
  const double k = kPi / 180.0;
  return Quat(Eigen::AngleAxisd(r.z() * k, Vec3::UnitZ()) * Eigen::AngleAxisd(r.y() * k, Vec3::UnitY()) *
              Eigen::AngleAxisd(r.x() * k, Vec3::UnitX()));
}

double exact_remainder(double x, double y) {
  if (x < y) return x;
  const double q = x / y;
  if (!(q < 0x1p52)) return std::fmod(x, y);
  // Dekker's product: n y = p + e exactly, each factor split into halves of 26 bits whose products are exact.
  const auto remainder_of = [&](double n) {
    constexpr double kSplit = 0x1p27 + 1.0;
    const double p = n * y;
    const double nc = kSplit * n, yc = kSplit * y;
    const double nh = nc - (nc - n), nl = n - nh, yh = yc - (yc - y), yl = y - yh;
    const double e = ((nh * yh - p) + nh * yl + nl * yh) + nl * yl;
    // x - p is exact (p lies within [x / 2, 2 x]); so is the remainder, which fmod's result always is.
    return (x - p) - e;
  };
  double n = static_cast<double>(static_cast<long long>(q));  // q >= 1: truncation is the whole part
  double r = remainder_of(n);
  if (r < 0.0) {
    r = remainder_of(n - 1.0);
  } else if (r >= y) {
    r = remainder_of(n + 1.0);
  }
  return r;
}

ScriptedMotion::ScriptedMotion(const MoverSpec& m)
    : orbit_(m.motion == MoverSpec::Motion::kOrbit), orientation_(orientation_deg(m.rotation_deg)) {
  if (m.motion == MoverSpec::Motion::kOrbit) {
    const Vec3 a = m.orbit.axis.normalized();
    const Vec3 ref = std::abs(a.x()) > 1.0 - 1e-12 ? Vec3::UnitY() : Vec3::UnitX();
    u_ = (ref - ref.dot(a) * a).normalized();
    v_ = a.cross(u_);
    center_ = m.orbit.center;
    radius_ = m.orbit.radius;
    period_ = m.orbit.period;
    phase_ = m.orbit.phase;
  } else if (m.motion == MoverSpec::Motion::kPath) {
    waypoints_ = m.path.waypoints;
    speed_ = m.path.speed;
    loop_ = m.path.loop;
    const auto& w = waypoints_;
    // Segments in travel order: 0..n-2 forward, then the closing one (loop) or the same ones backwards.
    for (std::size_t i = 0; i + 1 < w.size(); ++i) {
      lengths_.push_back((w[i + 1] - w[i]).norm());
      open_ += lengths_.back();
    }
    closing_ = (w.front() - w.back()).norm();
    cycle_ = m.path.loop ? open_ + closing_ : 2.0 * open_;
  }
}

Vec3 ScriptedMotion::position(double t) const {
  if (orbit_) {
    const double w = phase_ + 2.0 * kPi * t / period_;
    return center_ + radius_ * (std::cos(w) * u_ + std::sin(w) * v_);
  }
  const auto& w = waypoints_;
  double s = exact_remainder(speed_ * std::max(t, 0.0), cycle_);
  if (!loop_ && s > open_) s = cycle_ - s;  // on the way back: the same point as going out
  for (std::size_t i = 0; i < lengths_.size(); ++i) {
    const double len = lengths_[i];
    if (s <= len) return w[i] + (s / len) * (w[i + 1] - w[i]);
    s -= len;
  }
  // The closing segment of a loop.
  return closing_ > 0.0 ? Vec3(w.back() + (std::min(s, closing_) / closing_) * (w.front() - w.back())) : w.front();
}

Vec3 path_position(const PathMotion& path, double t) {
  MoverSpec m;
  m.motion = MoverSpec::Motion::kPath;
  m.path = path;
  return ScriptedMotion(m).pose(t).position;
}

Vec3 orbit_position(const OrbitMotion& orbit, double t) {
  MoverSpec m;
  m.motion = MoverSpec::Motion::kOrbit;
  m.orbit = orbit;
  return ScriptedMotion(m).pose(t).position;
}

Pose scripted_pose(const MoverSpec& m, double t) { return ScriptedMotion(m).pose(t); }

double scripted_speed(const MoverSpec& m) {
  return m.motion == MoverSpec::Motion::kOrbit ? 2.0 * kPi * m.orbit.radius / m.orbit.period : m.path.speed;
}

std::vector<Vec3> route_samples(const MoverSpec& m, double spacing) {
  std::vector<Vec3> out;
  if (m.motion == MoverSpec::Motion::kDynamic) return {m.start};
  if (m.motion == MoverSpec::Motion::kOrbit) {
    const int n = std::max(8, static_cast<int>(std::ceil(2.0 * kPi * m.orbit.radius / spacing)));
    for (int i = 0; i < n; ++i) out.push_back(orbit_position(m.orbit, m.orbit.period * i / n));
    return out;
  }
  const auto& w = m.path.waypoints;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const Vec3& a = w[i];
    const bool last = i + 1 == w.size();
    if (last && !m.path.loop) {
      out.push_back(a);
      break;
    }
    const Vec3& b = last ? w.front() : w[i + 1];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
    for (int k = 0; k < n; ++k) out.push_back(a + (double(k) / n) * (b - a));
  }
  return out;
}

std::string describe_mover(const MoverSpec& m, int id) {
  return fmt::format("{} mover {} ({})", to_string(m.shape.kind), id, to_string(m.motion));
}

}  // namespace peg3d::world
