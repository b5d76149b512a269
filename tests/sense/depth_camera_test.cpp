// A depth camera (sense/depth_camera.hpp) read through the sensor contract: pixel rays through the pixels' centres
// about the mounted axis, against a frame built here from rotations; every pixel's depth against analytic
// ray-plane, ray-sphere and ray-cylinder answers over random eyes, headings, mounts, fields of view and sizes, with
// pixels that graze a solid by a hair inside and miss it by a hair outside; noise and dropouts; its settings
// bounded.
#include "sense/depth_camera.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include "core/random.hpp"
#include "support/numbers.hpp"
#include "world/world_test_support.hpp"

namespace peg3d::sense {
namespace {

using testing::kDeg;

// Pixel (r, c)'s unit direction and the optical axis, in the world, built from the header's words with rotations:
// the sensor frame (x the heading, y level to its left, z = x cross y), turned up by the mount's elevation and left
// by its azimuth; in it the pixel looks along (f, -(c + 1/2 - W/2), -(r + 1/2 - H/2)), f = (W/2) / tan(hfov/2).
struct Expected {
  Eigen::Matrix3d camera;  // columns: the camera's x (optical axis), y (left), z (up) in the world
  double f = 1.0;
  int width = 0, height = 0;
  Expected(const DepthCameraConfig& c, const Heading& h) : width(c.width), height(c.height) {
    Eigen::Matrix3d sensor;
    const Vec3 x = direction(h), y(-std::sin(h.alpha), std::cos(h.alpha), 0.0);
    sensor << x, y, x.cross(y);
    camera = sensor * Eigen::AngleAxisd(c.mount_azimuth * kDeg, Vec3::UnitZ()).toRotationMatrix() *
             Eigen::AngleAxisd(-c.mount_elevation * kDeg, Vec3::UnitY()).toRotationMatrix();
    f = 0.5 * c.width / std::tan(0.5 * c.hfov * kDeg);
  }
  Vec3 axis() const { return camera.col(0); }
  Vec3 pixel(int r, int c) const {
    return (camera * Vec3(f, -(c + 0.5 - 0.5 * width), -(r + 0.5 - 0.5 * height))).normalized();
  }
};

// One image through the contract: scan() from `eye` heading `h`, with `balls` in the world (the holder is `self`).
struct Image {
  std::vector<double> depth;
  std::vector<std::uint8_t> echo;
};
Image scan(const DepthCamera& camera, const StaticRayScene& scene, const Vec3& eye, const Heading& h, Rng& rng,
           std::span<const Ball> balls = {}, int self = -1) {
  static std::unique_ptr<SensorScratch> scratch;
  scratch = camera.make_scratch();
  ScanContext context;
  context.world.scene = &scene;
  context.world.balls = balls;
  context.eye = eye;
  context.heading = h;
  context.self = self;
  Image out{std::vector<double>(std::size_t(camera.pixels())), std::vector<std::uint8_t>(std::size_t(camera.pixels()))};
  camera.scan(context, rng, {out.depth, out.echo}, scratch.get());
  return out;
}

// A random camera: size, field of view, mount and range.
DepthCameraConfig random_camera(Rng& rng, double range) {
  DepthCameraConfig c;
  c.width = 1 + int(uniform(rng, 0, 40));
  c.height = 1 + int(uniform(rng, 0, 30));
  c.hfov = uniform(rng, 5, 160);
  c.range = range;
  c.mount_azimuth = unit_uniform(rng) < 0.5 ? uniform(rng, -180, 180) : 0.0;
  c.mount_elevation = unit_uniform(rng) < 0.5 ? uniform(rng, -90, 90) : 0.0;
  return c;
}

Heading random_heading(Rng& rng) { return {uniform(rng, -kPi, kPi), uniform(rng, 0.2, kPi - 0.2)}; }

// An empty room from the origin; its faces are obstacles (rays end on them) or not.
std::shared_ptr<const world::Arena> room(const Vec3& size, bool faces, std::vector<world::SphereObstacle> spheres = {},
                                         std::vector<world::CylinderObstacle> cylinders = {}) {
  world::MapSpec m = world::testing::empty_spec(size, 2.0);  // (the distance field's cells: rays do not use them)
  m.floor_is_obstacle = m.ceiling_is_obstacle = m.walls_is_obstacle = faces;
  m.spheres = std::move(spheres);
  m.cylinders = std::move(cylinders);
  return world::Arena::build(m);
}

// Where a ray from `o` along unit `d` leaves the box [lo, hi] it starts in.
double box_exit(const Vec3& o, const Vec3& d, const Vec3& lo, const Vec3& hi) {
  double t = INFINITY;
  for (int k = 0; k < 3; ++k) {
    if (d[k] > 0) t = std::min(t, (hi[k] - o[k]) / d[k]);
    if (d[k] < 0) t = std::min(t, (lo[k] - o[k]) / d[k]);
  }
  return t;
}

// The first t >= 0 where the ray meets the ball (the nearer root of |o + t d - c|^2 = r^2), if any.
std::optional<double> sphere_entry(const Vec3& o, const Vec3& d, const Vec3& c, double r) {
  const Vec3 m = o - c;
  const double b = d.dot(m), disc = b * b - (m.squaredNorm() - r * r);
  if (disc < 0) return std::nullopt;
  const double t = -b - std::sqrt(disc);
  return t >= 0 ? std::optional(t) : std::nullopt;
}

// The first t >= 0 where the ray meets the upright cylinder: its side where the height is within [z0, z1], its
// caps where the circle holds the point; the smallest of those.
std::optional<double> cylinder_entry(const Vec3& o, const Vec3& d, const Vec3& base, double r, double height) {
  std::optional<double> best;
  const auto take = [&](double t) {
    if (t >= 0 && (!best || t < *best)) best = t;
  };
  const double z0 = base.z(), z1 = base.z() + height;
  const double px = o.x() - base.x(), py = o.y() - base.y();
  const double a = d.x() * d.x() + d.y() * d.y(), b = px * d.x() + py * d.y(), c = px * px + py * py - r * r;
  if (a > 0 && b * b - a * c >= 0) {
    for (const double t : {(-b - std::sqrt(b * b - a * c)) / a, (-b + std::sqrt(b * b - a * c)) / a}) {
      const double z = o.z() + t * d.z();
      if (z >= z0 && z <= z1) take(t);
    }
  }
  for (const double z : {z0, z1}) {
    if (d.z() == 0) continue;
    const double t = (z - o.z()) / d.z();
    const double x = px + t * d.x(), y = py + t * d.y();
    if (x * x + y * y <= r * r) take(t);
  }
  return best;
}

// Every pixel of `image` against `met(direction)`, the analytic first distance along the pixel's ray (nullopt: none
// within the range): an echo exactly where there is one, reading its depth along the optical axis, else the range.
template <class Met>
void expect_depths(const Image& image, const DepthCameraConfig& c, const Heading& h, const Met& met, int& echoes,
                   int& misses) {
  const Expected e(c, h);
  for (int r = 0; r < c.height; ++r) {
    for (int col = 0; col < c.width; ++col) {
      const std::size_t k = std::size_t(r * c.width + col);
      const Vec3 d = e.pixel(r, col);
      const std::optional<double> t = met(d);
      const bool hit = t && *t <= c.range;
      ASSERT_EQ(image.echo[k], hit ? 1 : 0) << "pixel " << r << "," << col << (t ? " at " + std::to_string(*t) : "");
      ASSERT_NEAR(image.depth[k], hit ? *t * d.dot(e.axis()) : c.range, 1e-9) << "pixel " << r << "," << col;
      echoes += hit, misses += !hit;
    }
  }
}

TEST(DepthCamera, PixelsLookThroughTheirCentresAboutTheMountedAxis) {
  Rng rng(1);
  for (int trial = 0; trial < 300; ++trial) {
    const DepthCameraConfig c = random_camera(rng, 10.0);
    const DepthCamera camera(c);
    ASSERT_EQ(camera.pixels(), c.width * c.height);
    const Heading h = random_heading(rng);
    const Vec3 eye(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5));
    std::vector<Ray> rays(std::size_t(camera.pixels()));
    camera.rays_at(eye, h, rays);
    const Expected e(c, h);
    const Pinhole p = camera.pinhole_at(h);
    for (int r = 0; r < c.height; ++r) {
      for (int col = 0; col < c.width; ++col) {
        const Ray& ray = rays[std::size_t(r * c.width + col)];
        ASSERT_EQ(ray.origin, eye);
        ASSERT_NEAR((ray.direction - e.pixel(r, col)).norm(), 0.0, 1e-14) << "pixel " << r << "," << col;
        // The pinhole's words: focal forward + (c + 1/2 - W/2) right + (r + 1/2 - H/2) down.
        const Vec3 through = p.focal * p.forward + (col + 0.5 - 0.5 * c.width) * p.right + (r + 0.5 - 0.5 * c.height) * p.down;
        ASSERT_NEAR((through.normalized() - ray.direction).norm(), 0.0, 1e-14);
        ASSERT_NEAR(camera.axis_cosine(r * c.width + col), ray.direction.dot(e.axis()), 1e-14);
      }
    }
  }
}

TEST(DepthCamera, AWallSquarelyAheadReadsOneDepthAtEveryPixel) {
  // The room's +x face straight ahead of a level heading: every pixel reads the eye's distance to it, the depth of
  // a plane facing the camera, not its rays' lengths.
  const auto arena = room({30, 20, 12}, true);
  const StaticRayScene scene(*arena);
  Rng rng(2);
  int images = 0;
  for (int trial = 0; trial < 40; ++trial) {
    DepthCameraConfig c;
    c.width = 8 + int(uniform(rng, 0, 60)), c.height = 6 + int(uniform(rng, 0, 40));
    c.hfov = uniform(rng, 10, 100);
    c.range = 40.0;
    const Vec3 eye(uniform(rng, 15, 28), uniform(rng, 9, 11), uniform(rng, 5, 7));
    // The view must lie within the face: half its width within 9 m of the eye's line, half its height within 5.
    const double half_width = (30.0 - eye.x()) * std::tan(0.5 * c.hfov * kDeg);
    if (half_width > 9.0 || half_width * c.height / c.width > 5.0) continue;
    Rng noise(3);
    const Image image = scan(DepthCamera(c), scene, eye, Heading{0.0, kPi / 2}, noise);
    for (std::size_t k = 0; k < image.depth.size(); ++k) {
      ASSERT_EQ(image.echo[k], 1);
      ASSERT_NEAR(image.depth[k], 30.0 - eye.x(), 1e-12) << "pixel " << k;
    }
    ++images;
  }
  EXPECT_GT(images, 25);
}

TEST(DepthCamera, EveryPixelOfARoomReadsTheDepthOfTheFaceItsRayMeets) {
  const Vec3 size(30, 20, 12);
  const auto arena = room(size, true);
  const StaticRayScene scene(*arena);
  Rng rng(4);
  int echoes = 0, misses = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const DepthCameraConfig c = random_camera(rng, uniform(rng, 2, 30));
    const Vec3 eye(uniform(rng, 0.5, 29.5), uniform(rng, 0.5, 19.5), uniform(rng, 0.5, 11.5));
    const Heading h = random_heading(rng);
    const Image image = scan(DepthCamera(c), scene, eye, h, rng);
    expect_depths(image, c, h, [&](const Vec3& d) { return std::optional(box_exit(eye, d, Vec3::Zero(), size)); },
                  echoes, misses);
  }
  EXPECT_GT(echoes, 10000);
  EXPECT_GT(misses, 1000);  // beyond the range
}

TEST(DepthCamera, SpheresReadTheirAnalyticDepthAndTheirRimsAreGrazedAndMissed) {
  Rng rng(5);
  int echoes = 0, misses = 0, grazed = 0, passed = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const DepthCameraConfig c = random_camera(rng, uniform(rng, 5, 25));
    const DepthCamera camera(c);
    const Vec3 eye(30, 30, 30);
    const Heading h = random_heading(rng);
    const Expected e(c, h);
    // One pixel's ray passes a sphere's centre at a hair less (or more) than its radius: that pixel grazes it (or
    // misses it); other spheres about the view.
    const int r0 = int(uniform(rng, 0, c.height - 0.01)), c0 = int(uniform(rng, 0, c.width - 0.01));
    const Vec3 d0 = e.pixel(r0, c0);
    const Vec3 side = d0.cross(Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1))).normalized();
    const bool inside = trial % 2 == 0;
    const double radius = uniform(rng, 0.2, 2.0), along = uniform(rng, radius + 0.5, c.range - 0.5);
    std::vector<world::SphereObstacle> spheres{{eye + along * d0 + radius * (inside ? 1 - 1e-7 : 1 + 1e-7) * side, radius}};
    for (int s = 0; s < 6; ++s) {
      const Vec3 at = eye + uniform(rng, 2, c.range) * e.pixel(int(uniform(rng, 0, c.height - 0.01)),
                                                               int(uniform(rng, 0, c.width - 0.01)));
      const double rs = uniform(rng, 0.1, 1.5);
      if ((at - eye).norm() > rs + 0.1) spheres.push_back({at + Vec3(uniform(rng, -1, 1), 0, 0), rs});
    }
    const auto arena = room({60, 60, 60}, false, spheres);
    const StaticRayScene scene(*arena);
    const Image image = scan(camera, scene, eye, h, rng);
    expect_depths(image, c, h,
                  [&](const Vec3& d) {
                    std::optional<double> best;
                    for (const auto& s : spheres) {
                      const auto t = sphere_entry(eye, d, s.center, s.radius);
                      if (t && (!best || *t < *best)) best = t;
                    }
                    return best;
                  },
                  echoes, misses);
    // The chosen pixel grazed the first sphere, or passed it, unless another sphere stood in front.
    const std::size_t k = std::size_t(r0 * c.width + c0);
    if (inside) grazed += image.echo[k] == 1;
    passed += !inside && image.echo[k] == 0;
  }
  std::printf("spheres: %d echoes, %d misses, %d grazed, %d passed\n", echoes, misses, grazed, passed);
  EXPECT_GT(echoes, 1000);
  EXPECT_GT(misses, 1000);
  EXPECT_GT(grazed, 50);
  EXPECT_GT(passed, 30);
}

TEST(DepthCamera, CylindersReadTheirSidesAndCapsAndTheirEdgesAreGrazedAndMissed) {
  Rng rng(6);
  int echoes = 0, misses = 0, grazed = 0, passed = 0;
  for (int trial = 0; trial < 150; ++trial) {
    DepthCameraConfig c = random_camera(rng, uniform(rng, 5, 25));
    const bool from_above = trial % 3 == 0;  // looking down on the caps
    if (from_above) c.mount_elevation = uniform(rng, -90, -30);
    const DepthCamera camera(c);
    const Vec3 eye(30, 30, from_above ? 40 : 30);
    const Heading h = random_heading(rng);
    const Expected e(c, h);
    // One pixel's ray passes a trunk's axis at a hair less (or more) than its radius, level with the trunk's
    // middle: it grazes the side (or misses it).
    const int r0 = int(uniform(rng, 0, c.height - 0.01)), c0 = int(uniform(rng, 0, c.width - 0.01));
    const Vec3 d0 = e.pixel(r0, c0);
    const bool inside = trial % 2 == 0;
    std::vector<world::CylinderObstacle> cylinders;
    const double radius = uniform(rng, 0.2, 1.5), along = uniform(rng, 3.0, c.range - 0.5);
    const Vec3 flat(d0.x(), d0.y(), 0);
    if (flat.norm() > 0.2) {
      // Seen from above, the ray is a line and the axis a point: the axis s across the line from the ray's point
      // `along` it lies s from the line, so the side is met (s < radius) or not.
      const Vec3 across = Vec3(-d0.y(), d0.x(), 0).normalized();
      const Vec3 p = eye + along * d0;
      const double s = radius * (inside ? 1 - 1e-7 : 1 + 1e-7);
      const Vec3 base = p + s * across - Vec3(0, 0, 2.0);
      cylinders.push_back({Vec3(base.x(), base.y(), base.z()), radius, 4.0});
    }
    for (int k = 0; k < 6; ++k) {
      const Vec3 at = eye + uniform(rng, 2, c.range) * e.pixel(int(uniform(rng, 0, c.height - 0.01)),
                                                               int(uniform(rng, 0, c.width - 0.01)));
      const double rc = uniform(rng, 0.1, 1.5), height = uniform(rng, 0.5, 6);
      const Vec3 base = at - Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, 0, height));
      if (Vec3(eye.x() - base.x(), eye.y() - base.y(), 0).norm() > rc + 0.1 || eye.z() < base.z() - 0.1 ||
          eye.z() > base.z() + height + 0.1) {
        cylinders.push_back({base, rc, height});
      }
    }
    const auto arena = room({60, 60, 60}, false, {}, cylinders);
    const StaticRayScene scene(*arena);
    const Image image = scan(camera, scene, eye, h, rng);
    expect_depths(image, c, h,
                  [&](const Vec3& d) {
                    std::optional<double> best;
                    for (const auto& cy : cylinders) {
                      const auto t = cylinder_entry(eye, d, cy.base, cy.radius, cy.height);
                      if (t && (!best || *t < *best)) best = t;
                    }
                    return best;
                  },
                  echoes, misses);
    const std::size_t k = std::size_t(r0 * c.width + c0);
    if (flat.norm() > 0.2) {
      if (inside) grazed += image.echo[k] == 1;
      passed += !inside && image.echo[k] == 0;
    }
  }
  std::printf("cylinders: %d echoes, %d misses, %d grazed, %d passed\n", echoes, misses, grazed, passed);
  EXPECT_GT(echoes, 1000);
  EXPECT_GT(misses, 1000);
  EXPECT_GT(grazed, 30);
  EXPECT_GT(passed, 20);
}

TEST(DepthCamera, OtherAgentsAreSeenButNotItsHolderUnlessTheSettingSaysOtherwise) {
  const auto arena = room({30, 30, 30}, false);
  const StaticRayScene scene(*arena);
  const Vec3 eye(10, 15, 15);
  const std::vector<Ball> balls{{eye, 0.5}, {Vec3(14, 15, 15), 1.0}};  // the holder, and an agent 4 m ahead
  for (const bool sees : {true, false}) {
    DepthCameraConfig c;
    c.width = 16, c.height = 12, c.hfov = 60, c.sees_agents = sees;
    Rng rng(7);
    const Image image = scan(DepthCamera(c), scene, eye, Heading{0.0, kPi / 2}, rng, balls, 0);
    const std::size_t centre = std::size_t(6 * 16 + 8);
    EXPECT_EQ(image.echo[centre], sees ? 1 : 0);
    if (sees) {
      const Expected e(c, Heading{0.0, kPi / 2});
      const Vec3 d = e.pixel(6, 8);
      EXPECT_NEAR(image.depth[centre], *sphere_entry(eye, d, balls[1].centre, 1.0) * d.dot(e.axis()), 1e-12);
    }
    int echoes = 0;
    for (const std::uint8_t e : image.echo) echoes += e;
    EXPECT_LT(echoes, 16 * 12);  // the agent, not the holder's own sphere around the eye
  }
}

TEST(DepthCamera, NoiseAndDropoutsFollowTheirSettingsFromTheHoldersStream) {
  const auto arena = room({30, 20, 12}, true);
  const StaticRayScene scene(*arena);
  DepthCameraConfig c;
  c.width = 64, c.height = 48, c.hfov = 40, c.range = 20, c.noise = 0.05, c.dropout = 0.2;
  const DepthCamera camera(c);
  const Vec3 eye(20, 10, 6);  // 10 m from the face ahead
  std::vector<double> echoed;
  int dropped = 0, pixels = 0;
  for (int image = 0; image < 20; ++image) {
    Rng rng(std::uint64_t(100 + image));
    const Image i = scan(camera, scene, eye, Heading{0.0, kPi / 2}, rng);
    for (std::size_t k = 0; k < i.depth.size(); ++k, ++pixels) {
      if (i.echo[k] == 0) {
        ++dropped;
        ASSERT_EQ(i.depth[k], 20.0);
      } else {
        echoed.push_back(i.depth[k]);
      }
    }
  }
  const double n = double(echoed.size());
  double mean = 0, var = 0;
  for (const double d : echoed) mean += d / n;
  for (const double d : echoed) var += (d - mean) * (d - mean) / (n - 1);
  EXPECT_NEAR(double(dropped) / pixels, 0.2, 5 * std::sqrt(0.2 * 0.8 / pixels));
  EXPECT_NEAR(mean, 10.0, 5 * 0.05 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(var), 0.05, 5 * 0.05 / std::sqrt(2 * n));
  // The same stream, the same image; another stream, another.
  Rng a(9), b(9), other(10);
  const Image first = scan(camera, scene, eye, Heading{0.0, kPi / 2}, a);
  const Image again = scan(camera, scene, eye, Heading{0.0, kPi / 2}, b);
  const Image different = scan(camera, scene, eye, Heading{0.0, kPi / 2}, other);
  EXPECT_EQ(first.depth, again.depth);
  EXPECT_EQ(first.echo, again.echo);
  EXPECT_NE(first.depth, different.depth);
}

TEST(DepthCamera, ItsSegmentIsTheImageOfHeightRowsAndWidthColumnsWithinTheRange) {
  DepthCameraConfig c;
  c.width = 64, c.height = 48, c.range = 12;
  std::vector<Segment> out;
  DepthCamera(c).segments({}, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].name, "camera.depth");
  EXPECT_EQ(out[0].size, 64 * 48);
  EXPECT_EQ(out[0].unit, "m");
  EXPECT_EQ(out[0].shape, (std::vector<int>{48, 64}));
  EXPECT_EQ(out[0].low.front(), 0.0);
  EXPECT_EQ(out[0].high.back(), 12.0);
}

TEST(DepthCamera, SettingsAreBounded) {
  const auto refused = [](DepthCameraConfig c, const char* field) {
    try {
      config::validate(c);
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted " << field;
  };
  DepthCameraConfig c;
  config::validate(c);  // the default: no camera
  c.width = 256, c.height = 256;
  config::validate(c);  // 65536 pixels: the most
  c.height = 257;
  refused(c, "height");
  c = {}, c.width = 1025;
  refused(c, "width");
  c = {}, c.hfov = 175;
  refused(c, "hfov");
  c = {}, c.range = 0;
  refused(c, "range");
  c = {}, c.period = 0;
  refused(c, "period");
  c = {}, c.dropout = -0.1;
  refused(c, "dropout");
  c = {}, c.noise = std::nan("");
  refused(c, "noise");
  c = {}, c.mount_elevation = 91;
  refused(c, "mount_elevation");
}

}  // namespace
}  // namespace peg3d::sense
