#include "view/frame_renderer.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/validation.hpp"
#include "geometry/angles.hpp"
#include "world/bodies/mover_timeline.hpp"
#include "world/bodies/push_world.hpp"

namespace peg3d::view {
namespace {

constexpr float kFar = std::numeric_limits<float>::infinity();
constexpr double kNear = 0.05;  // m: triangles reaching closer than this to the camera are not drawn

using Colour = const std::uint8_t (&)[3];

// Tessellations, fine enough at 640 x 480 for the ball of a shape a few metres off to look round.
constexpr int kSphereStacks = 10, kSphereSlices = 16, kCylinderSlices = 20;

template <class Emit>
void sphere_triangles(const Vec3& c, double r, Emit&& emit) {
  const auto at = [&](int i, int j) {
    const double th = kPi * i / kSphereStacks, ph = 2.0 * kPi * j / kSphereSlices;
    return Vec3(c + r * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
  };
  for (int i = 0; i < kSphereStacks; ++i) {
    for (int j = 0; j < kSphereSlices; ++j) {
      const Vec3 a = at(i, j), b = at(i + 1, j), d = at(i, j + 1), e = at(i + 1, j + 1);
      if (i > 0) emit(a, b, d);
      if (i + 1 < kSphereStacks) emit(d, b, e);
    }
  }
}

// A cylinder of the given axis frame (centre of its base, unit axis, two unit perpendiculars).
template <class Emit>
void cylinder_triangles(const Vec3& base, const Vec3& axis, const Vec3& u, const Vec3& v, double r, double h, Emit&& emit) {
  const Vec3 top = base + h * axis;
  for (int j = 0; j < kCylinderSlices; ++j) {
    const double a0 = 2.0 * kPi * j / kCylinderSlices, a1 = 2.0 * kPi * (j + 1) / kCylinderSlices;
    const Vec3 d0 = r * (std::cos(a0) * u + std::sin(a0) * v), d1 = r * (std::cos(a1) * u + std::sin(a1) * v);
    emit(Vec3(base + d0), Vec3(base + d1), Vec3(top + d1));
    emit(Vec3(base + d0), Vec3(top + d1), Vec3(top + d0));
    emit(base, Vec3(base + d1), Vec3(base + d0));
    emit(top, Vec3(top + d0), Vec3(top + d1));
  }
}

template <class Emit>
void posed_shape_triangles(const Shape& s, const Pose& p, Emit&& emit) {
  const Eigen::Matrix3d r = p.orientation.toRotationMatrix();
  switch (s.kind) {
    case Shape::Kind::kSphere:
      sphere_triangles(p.position, s.radius, emit);
      break;
    case Shape::Kind::kCylinder:
      cylinder_triangles(Vec3(p.position - 0.5 * s.height * r.col(2)), r.col(2), r.col(0), r.col(1), s.radius, s.height,
                         emit);
      break;
    case Shape::Kind::kBox: {
      const Vec3 h = 0.5 * s.size;
      const auto corner = [&](int k) {
        return Vec3(p.position + r * Vec3((k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(), (k & 4 ? 1 : -1) * h.z()));
      };
      // The six faces as corner quadruples (bits: x, y, z).
      static constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
      for (const auto& f : kFaces) {
        emit(corner(f[0]), corner(f[1]), corner(f[2]));
        emit(corner(f[0]), corner(f[2]), corner(f[3]));
      }
      break;
    }
  }
}

}  // namespace

FrameRenderer::FrameRenderer(const game::Sim& sim, const FrameSettings& settings) : sim_(sim), settings_(settings) {
  require_in_range("width", settings.width, 16, 4096);
  require_in_range("height", settings.height, 16, 4096);
  if (!(settings.vertical_fov > 10.0 && settings.vertical_fov < 120.0)) {
    throw InvalidParameter("vertical_fov", std::to_string(settings.vertical_fov), "must lie in (10, 120) deg");
  }
  // The camera: above the arena's south-west side, looking at its centre, its whole box in view.
  const Box& box = sim.arena().bounds();
  const Vec3 centre = 0.5 * (box.lo + box.hi);
  const double half_fov = 0.5 * settings.vertical_fov * kPi / 180.0;
  const double aspect = double(settings.width) / settings.height;
  focal_ = 0.5 * settings.height / std::tan(half_fov);
  const Vec3 back = Vec3(-0.35, -0.8, 0.5).normalized();
  forward_ = -back;
  right_ = forward_.cross(Vec3::UnitZ()).normalized();
  up_ = right_.cross(forward_);
  // The nearest eye on that line from which all eight corners of the box fall within 3 % of the image's edges
  // (farther is always safe, so bisect between the bounding ball's distance and a tenth of it).
  const auto fits = [&](double reach) {
    eye_ = centre + reach * back;
    for (int k = 0; k < 8; ++k) {
      const Vec3 p = project(Vec3(k & 1 ? box.hi.x() : box.lo.x(), k & 2 ? box.hi.y() : box.lo.y(), k & 4 ? box.hi.z() : box.lo.z()));
      if (p.z() <= kNear || p.x() < 0.03 * settings.width || p.x() > 0.97 * settings.width ||
          p.y() < 0.03 * settings.height || p.y() > 0.97 * settings.height) {
        return false;
      }
    }
    return true;
  };
  double far = 0.5 * (box.hi - box.lo).norm() / std::sin(half_fov * std::min(1.0, aspect)), near = 0.1 * far;
  for (int i = 0; i < 40; ++i) (fits(0.5 * (near + far)) ? far : near) = 0.5 * (near + far);
  eye_ = centre + far * back;

  const std::size_t pixels = std::size_t(settings.width) * std::size_t(settings.height);
  base_rgb_.resize(3 * pixels);
  base_depth_.assign(pixels, kFar);
  // The sky: a gradient from blue at the top to pale at the bottom.
  for (int y = 0; y < settings.height; ++y) {
    const double s = double(y) / (settings.height - 1);
    const std::uint8_t sky[3] = {std::uint8_t(100 + 100 * s), std::uint8_t(150 + 70 * s), std::uint8_t(230 + 10 * s)};
    for (int x = 0; x < settings.width; ++x) std::memcpy(&base_rgb_[3 * (std::size_t(y) * settings.width + x)], sky, 3);
  }
  std::vector<Triangle> fixed;
  const auto add = [&](Colour colour) {
    return [&fixed, r = colour[0], g = colour[1], b = colour[2]](const Vec3& p, const Vec3& q, const Vec3& s) {
      fixed.push_back({p, q, s, {r, g, b}});
    };
  };
  // The floor: a checkerboard of 1 m tiles (at most 64 a side), two greys.
  const int nx = std::clamp(int(std::ceil(box.hi.x() - box.lo.x())), 1, 64);
  const int ny = std::clamp(int(std::ceil(box.hi.y() - box.lo.y())), 1, 64);
  static constexpr std::uint8_t kLight[3] = {205, 205, 200}, kDark[3] = {175, 175, 170};
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const double x0 = box.lo.x() + (box.hi.x() - box.lo.x()) * i / nx, x1 = box.lo.x() + (box.hi.x() - box.lo.x()) * (i + 1) / nx;
      const double y0 = box.lo.y() + (box.hi.y() - box.lo.y()) * j / ny, y1 = box.lo.y() + (box.hi.y() - box.lo.y()) * (j + 1) / ny;
      const double z = box.lo.z();
      auto tile = add((i + j) % 2 ? kDark : kLight);
      tile(Vec3(x0, y0, z), Vec3(x1, y0, z), Vec3(x1, y1, z));
      tile(Vec3(x0, y0, z), Vec3(x1, y1, z), Vec3(x0, y1, z));
    }
  }
  const world::MapSpec& map = sim.arena().map();
  for (const auto& s : map.spheres) sphere_triangles(s.center, s.radius, add(FramePalette::kObstacle));
  for (const auto& c : map.cylinders) {
    cylinder_triangles(c.base, Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY(), c.radius, c.height, add(FramePalette::kObstacle));
  }
  for (const auto& mesh : sim.arena().meshes()) {
    auto emit = add(FramePalette::kTerrain);
    for (const auto& f : mesh.faces) {
      emit(mesh.vertices[std::size_t(f[0])], mesh.vertices[std::size_t(f[1])], mesh.vertices[std::size_t(f[2])]);
    }
  }
  for (const Triangle& t : fixed) draw(t, base_rgb_, base_depth_);
  rgb_ = base_rgb_;
  depth_ = base_depth_;
}

Vec3 FrameRenderer::project(const Vec3& p) const {
  const Vec3 d = p - eye_;
  const double z = d.dot(forward_);
  if (z <= 0.0) return {0.0, 0.0, z};
  return {0.5 * settings_.width + focal_ * d.dot(right_) / z, 0.5 * settings_.height - focal_ * d.dot(up_) / z, z};
}

void FrameRenderer::draw(const Triangle& t, std::vector<std::uint8_t>& rgb, std::vector<float>& depth) const {
  const Vec3 pa = project(t.a), pb = project(t.b), pc = project(t.c);
  if (pa.z() < kNear || pb.z() < kNear || pc.z() < kNear) return;
  // Flat shading: a light from above and behind the camera, both faces lit alike (meshes' windings vary).
  const Vec3 n = (t.b - t.a).cross(t.c - t.a);
  const double len = n.norm();
  if (!(len > 0.0)) return;
  static const Vec3 kLight = Vec3(-0.3, -0.5, 1.0).normalized();
  const double shade = 0.45 + 0.55 * std::abs(n.dot(kLight)) / len;
  const std::uint8_t colour[3] = {std::uint8_t(t.colour[0] * shade), std::uint8_t(t.colour[1] * shade),
                                  std::uint8_t(t.colour[2] * shade)};
  const double area = (pb.x() - pa.x()) * (pc.y() - pa.y()) - (pb.y() - pa.y()) * (pc.x() - pa.x());
  if (std::abs(area) < 1e-12) return;
  const int w = settings_.width, h = settings_.height;
  const int x0 = std::max(0, int(std::floor(std::min({pa.x(), pb.x(), pc.x()}))));
  const int x1 = std::min(w - 1, int(std::ceil(std::max({pa.x(), pb.x(), pc.x()}))));
  const int y0 = std::max(0, int(std::floor(std::min({pa.y(), pb.y(), pc.y()}))));
  const int y1 = std::min(h - 1, int(std::ceil(std::max({pa.y(), pb.y(), pc.y()}))));
  // Depth is interpolated as 1/z, which is affine in screen space.
  const double ia = 1.0 / pa.z(), ib = 1.0 / pb.z(), ic = 1.0 / pc.z();
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      const double wa = ((pb.x() - px) * (pc.y() - py) - (pb.y() - py) * (pc.x() - px)) / area;
      const double wb = ((pc.x() - px) * (pa.y() - py) - (pc.y() - py) * (pa.x() - px)) / area;
      const double wc = 1.0 - wa - wb;
      if (wa < 0.0 || wb < 0.0 || wc < 0.0) continue;
      const float z = float(1.0 / (wa * ia + wb * ib + wc * ic));
      const std::size_t k = std::size_t(y) * std::size_t(w) + std::size_t(x);
      if (z >= depth[k]) continue;
      depth[k] = z;
      std::memcpy(&rgb[3 * k], colour, 3);
    }
  }
}

void FrameRenderer::render(const game::SimState& state, std::span<std::uint8_t> rgb) {
  assert(rgb.size() == base_rgb_.size());
  std::memcpy(rgb_.data(), base_rgb_.data(), rgb_.size());
  std::memcpy(depth_.data(), base_depth_.data(), depth_.size() * sizeof(float));
  scratch_.clear();
  const auto add = [this](Colour colour) {
    return [this, r = colour[0], g = colour[1], b = colour[2]](const Vec3& p, const Vec3& q, const Vec3& s) {
      scratch_.push_back({p, q, s, {r, g, b}});
    };
  };
  const world::MapSpec& map = sim_.arena().map();
  for (int m = 0; m < int(map.movers.size()); ++m) {
    const world::MoverSpec& spec = map.movers[std::size_t(m)];
    Pose pose;
    if (state.push) {
      pose = state.push->pose(m);
    } else if (const world::MoverTimeline* timeline = sim_.movers(); timeline && m < timeline->count()) {
      pose = timeline->pose(m, state.time);
    } else {
      continue;
    }
    posed_shape_triangles(spec.shape, pose, add(spec.kinematic() ? FramePalette::kMover : FramePalette::kBody));
  }
  for (const game::AgentState& a : state.agents) {
    const Colour colour = !a.active ? FramePalette::kInactive
                          : a.role == game::Role::kPursuer ? FramePalette::kPursuer
                                                            : FramePalette::kEvader;
    sphere_triangles(a.kinematics.position, std::max(a.config->radius, settings_.min_agent_radius), add(colour));
  }
  for (const Triangle& t : scratch_) draw(t, rgb_, depth_);
  std::memcpy(rgb.data(), rgb_.data(), rgb_.size());
}

}  // namespace peg3d::view
