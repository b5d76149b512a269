// The vertical-ray index answers exactly as the scan of every triangle, on vertices, edges, cell borders
// and random points, for a height field and for a jumble of triangles.
#include "world/map/obstacle_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace peg3d::world {
namespace {

// A height field of n x n quads over [0, 10]^2 plus a few large and sliver triangles across it.
TriangleMesh terrain(int n) {
  TriangleMesh m;
  const double step = 10.0 / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(i * step, j * step, 2.0 + std::sin(0.7 * i) * std::cos(0.4 * j));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  }
  const int base = int(m.vertices.size());
  for (const Vec3& v : {Vec3(-1, -1, 5), Vec3(11, 0, 5), Vec3(5, 11, 5), Vec3(3, 3, 7), Vec3(3.001, 9, 7), Vec3(3, 9.5, 7)}) {
    m.vertices.push_back(v);
  }
  m.faces.push_back({base, base + 1, base + 2});      // a large one over everything, at z = 5
  m.faces.push_back({base + 3, base + 4, base + 5});  // a sliver
  return m;
}

TEST(WorldVerticalRayIndex, AnswersAsTheScanOfEveryTriangle) {
  const TriangleMesh m = terrain(40);
  const VerticalRayIndex index(m);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> xy(-2.0, 12.0), z(0.0, 8.0);
  int below = 0, checked = 0;
  const auto agree = [&](const Vec3& p) {
    const bool expected = is_below_surface(m, p);
    below += expected;
    ++checked;
    ASSERT_EQ(index.is_below_surface(m, p), expected) << p.transpose();
  };
  for (int k = 0; k < 20000; ++k) agree(Vec3(xy(rng), xy(rng), z(rng)));
  for (const Vec3& v : m.vertices) {  // on every vertex, just under and just over it
    agree(v - Vec3(0, 0, 1e-9));
    agree(v + Vec3(0, 0, 1e-9));
  }
  for (int k = 0; k <= 400; ++k) agree(Vec3(k * 0.025, 10.0 - k * 0.025, 1.5));  // along a diagonal, across cells
  EXPECT_GT(below, checked / 10);
  EXPECT_LT(below, checked - checked / 10);
}

TEST(WorldVerticalRayIndex, AnEmptyIndexScansEveryTriangle) {
  const TriangleMesh m = terrain(4);
  const VerticalRayIndex none;
  EXPECT_TRUE(none.is_below_surface(m, Vec3(5, 5, 0.5)));
  EXPECT_FALSE(none.is_below_surface(m, Vec3(5, 5, 9)));
}

}  // namespace
}  // namespace peg3d::world
