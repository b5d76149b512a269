// A lidar's rays and readings (sense/lidar.hpp): directions against the sensor frame's analytic angles over random
// headings and layouts; noise and dropout against their distributions; its settings bounded.
#include "sense/lidar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/config_fields.hpp"
#include "support/numbers.hpp"

namespace peg3d::sense {
namespace {

using testing::kDeg;

TEST(Lidar, RaysLieAtTheCellCentresOfTheFieldOfViewAboutTheHeading) {
  Rng rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    LidarConfig c;
    c.azimuth_rays = 1 + int(u(rng) * 24);
    c.elevation_rays = 1 + int(u(rng) * 6);
    c.azimuth_fov = 1.0 + 359.0 * u(rng);
    c.elevation_fov = 170.0 * u(rng);
    c.mount_azimuth = -180.0 + 360.0 * u(rng);
    c.mount_elevation = -5.0 + 10.0 * u(rng);
    const Lidar lidar(c);
    ASSERT_EQ(lidar.rays(), c.azimuth_rays * c.elevation_rays);
    // A heading anywhere, pitched up to 60 degrees.
    const Heading h{-kPi + 2 * kPi * u(rng), kPi / 2 + (u(rng) - 0.5) * 120.0 * kDeg};
    const Vec3 origin(u(rng), u(rng), u(rng));
    std::vector<Ray> rays(std::size_t(lidar.rays()));
    lidar.rays_at(origin, h, rays);
    // The frame: x the heading, y level and to its left, z = x cross y.
    const Vec3 x = direction(h), y(-std::sin(h.alpha), std::cos(h.alpha), 0.0), z = x.cross(y);
    for (int j = 0; j < c.elevation_rays; ++j) {
      for (int i = 0; i < c.azimuth_rays; ++i) {
        const Ray& r = rays[std::size_t(j * c.azimuth_rays + i)];
        const double a = (c.mount_azimuth + c.azimuth_fov * ((i + 0.5) / c.azimuth_rays - 0.5)) * kDeg;
        const double e = (c.mount_elevation + c.elevation_fov * ((j + 0.5) / c.elevation_rays - 0.5)) * kDeg;
        ASSERT_EQ(r.origin, origin);
        ASSERT_NEAR(r.direction.norm(), 1.0, 1e-12);
        ASSERT_NEAR(r.direction.dot(z), std::sin(e), 1e-12) << "ray " << i << "," << j;
        ASSERT_NEAR(r.direction.dot(x), std::cos(e) * std::cos(a), 1e-12) << "ray " << i << "," << j;
        ASSERT_NEAR(r.direction.dot(y), std::cos(e) * std::sin(a), 1e-12) << "ray " << i << "," << j;
      }
    }
  }
}

TEST(Lidar, OneRayLooksAlongTheHeadingAndAFullCircleSpreadsEvenly) {
  LidarConfig one;
  one.azimuth_rays = 1;
  std::vector<Ray> ray(1);
  const Heading h{0.7, 1.1};
  Lidar(one).rays_at(Vec3::Zero(), h, ray);
  EXPECT_NEAR((ray[0].direction - direction(h)).norm(), 0.0, 1e-15);
  LidarConfig ring;
  ring.azimuth_rays = 4;  // 360 degrees: -135, -45, 45, 135 from a level heading along +x
  std::vector<Ray> rays(4);
  Lidar(ring).rays_at(Vec3::Zero(), Heading{0.0, kPi / 2}, rays);
  const double s = std::sqrt(0.5);
  const Vec3 want[] = {{-s, -s, 0}, {s, -s, 0}, {s, s, 0}, {-s, s, 0}};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR((rays[std::size_t(k)].direction - want[k]).norm(), 0.0, 1e-15) << k;
}

std::vector<RayHit> hits_at(double d, int n) { return std::vector<RayHit>(std::size_t(n), RayHit{d, RayTarget::kSphere, 0}); }

TEST(Lidar, NoiseIsGaussianWithTheConfiguredSigmaAndClampedToTheRange) {
  for (const double sigma : {0.01, 0.3}) {
    LidarConfig c;
    c.range = 10.0;
    c.noise = sigma;
    const int n = 200000;
    const auto hits = hits_at(4.0, n);
    std::vector<double> ranges(n);
    std::vector<std::uint8_t> echo(n);
    Rng rng(3);
    read_out(c, hits, rng, ranges, echo);
    double mean = 0, var = 0, within = 0;
    for (double r : ranges) mean += r;
    mean /= n;
    for (double r : ranges) var += (r - mean) * (r - mean), within += std::abs(r - 4.0) <= sigma;
    var /= n - 1;
    // Standard errors: sigma / sqrt(n) for the mean, about sigma / sqrt(2n) for the deviation; 5 of them.
    EXPECT_NEAR(mean, 4.0, 5 * sigma / std::sqrt(n));
    EXPECT_NEAR(std::sqrt(var), sigma, 5 * sigma / std::sqrt(2.0 * n));
    EXPECT_NEAR(within / n, 0.682689, 0.005);  // P(|Z| <= 1)
    for (std::uint8_t e : echo) ASSERT_EQ(e, 1);
  }
  // Near the ends the readings stay in [0, range].
  LidarConfig c;
  c.range = 1.0;
  c.noise = 0.5;
  const auto near = hits_at(0.05, 1000), far = hits_at(0.97, 1000);
  std::vector<double> ranges(1000);
  std::vector<std::uint8_t> echo(1000);
  Rng rng(4);
  for (const auto* h : {&near, &far}) {
    read_out(c, *h, rng, ranges, echo);
    int at_end = 0;
    for (double r : ranges) {
      ASSERT_GE(r, 0.0);
      ASSERT_LE(r, 1.0);
      at_end += r == 0.0 || r == 1.0;
    }
    EXPECT_GT(at_end, 300);
  }
}

TEST(Lidar, DropoutsReadTheRangeWithoutAnEchoAtTheConfiguredRate) {
  for (const double p : {0.0, 0.05, 0.5, 1.0}) {
    LidarConfig c;
    c.range = 7.0;
    c.dropout = p;
    const int n = 100000;
    const auto hits = hits_at(2.5, n);
    std::vector<double> ranges(n);
    std::vector<std::uint8_t> echo(n);
    Rng rng(9);
    read_out(c, hits, rng, ranges, echo);
    int dropped = 0;
    for (int k = 0; k < n; ++k) {
      if (echo[std::size_t(k)] == 0) {
        ++dropped;
        ASSERT_EQ(ranges[std::size_t(k)], 7.0);
      } else {
        ASSERT_EQ(ranges[std::size_t(k)], 2.5);
      }
    }
    EXPECT_NEAR(double(dropped) / n, p, 5 * std::sqrt(p * (1 - p) / n) + 1e-12) << p;
  }
}

TEST(Lidar, ARayThatMeetsNothingReadsTheRangeWithoutAnEcho) {
  LidarConfig c;
  c.range = 3.0;
  c.noise = 0.1;
  const std::vector<RayHit> hits{{3.0, RayTarget::kNone, -1}, {1.0, RayTarget::kArenaFace, 5}};
  std::vector<double> ranges(2);
  std::vector<std::uint8_t> echo(2);
  Rng rng(1);
  read_out(c, hits, rng, ranges, echo);
  EXPECT_EQ(echo[0], 0);
  EXPECT_EQ(ranges[0], 3.0);
  EXPECT_EQ(echo[1], 1);
  EXPECT_NE(ranges[1], 1.0);  // noisy
}

TEST(Lidar, TheSameStreamGivesTheSameReadings) {
  LidarConfig c;
  c.noise = 0.2;
  c.dropout = 0.3;
  const auto hits = hits_at(5.0, 1000);
  std::vector<double> a(1000), b(1000);
  std::vector<std::uint8_t> ea(1000), eb(1000);
  Rng r1(77), r2(77);
  read_out(c, hits, r1, a, ea);
  read_out(c, hits, r2, b, eb);
  EXPECT_EQ(a, b);
  EXPECT_EQ(ea, eb);
}

TEST(Lidar, SettingsAreBounded) {
  const auto refused = [](LidarConfig c, const char* field) {
    try {
      config::validate(c);
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted " << field;
  };
  LidarConfig c;
  config::validate(c);  // the default: no lidar
  c.azimuth_rays = 256, c.elevation_rays = 256;
  config::validate(c);  // 65536 rays: the most
  c.elevation_rays = 257;
  refused(c, "elevation_rays");
  c = {}, c.azimuth_rays = 31623, c.elevation_rays = 31623;  // 10^9 rays
  refused(c, "elevation_rays");
  c = {}, c.azimuth_rays = 1000000000;
  refused(c, "azimuth_rays");
  c = {}, c.range = 0.0;
  refused(c, "range");
  c = {}, c.period = 0;
  refused(c, "period");
  c = {}, c.dropout = 1.5;
  refused(c, "dropout");
  c = {}, c.noise = -0.1;
  refused(c, "noise");
  c = {}, c.azimuth_fov = 0.0;
  refused(c, "azimuth_fov");
  c = {}, c.elevation_fov = std::nan("");
  refused(c, "elevation_fov");
}

}  // namespace
}  // namespace peg3d::sense
