// An agent's map from its scans (sense/scan_map.hpp) against OctoMap's own insertPointCloud: the same scans, taken
// by a lidar along a random walk through forest's trunks and valley's terrain, give every cell inside the arena the
// same log-odds, bit for bit, at several resolutions and sensor models; ranges beyond max_range carve free space
// only; clear() forgets; a box too fine for memory is refused.
#include "sense/scan_map.hpp"

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <set>

#include "core/error.hpp"
#include "core/random.hpp"
#include "core/validation.hpp"
#include "sense/lidar.hpp"
#include "sense/world_rays.hpp"
#include "world/map/map_loader.hpp"

namespace peg3d::sense {
namespace {

// Every cell OctoMap holds inside the map's box equals the map's, and the map knows no other cell.
void expect_same_cells(const ScanMap& map, octomap::OcTree& tree, const Vec3& lo, const Vec3& hi, const char* what) {
  tree.expand();  // pruned nodes become their cells
  const CellKey a = map.key_of(lo), b = map.key_of(hi);
  long long inside = 0, mismatches = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    ASSERT_EQ(it.getDepth(), tree.getTreeDepth());
    const octomap::OcTreeKey k = it.getKey();
    bool in = true;
    for (int d = 0; d < 3; ++d) in = in && k[d] >= a[std::size_t(d)] && k[d] <= b[std::size_t(d)];
    if (!in) continue;
    ++inside;
    const float mine = map.log_odds({k[0], k[1], k[2]});
    if (mine != it->getLogOdds()) {
      if (++mismatches <= 5) ADD_FAILURE() << what << ": cell " << k[0] << "," << k[1] << "," << k[2] << " octomap "
                                           << it->getLogOdds() << " map " << mine;
    }
  }
  EXPECT_EQ(mismatches, 0) << what;
  EXPECT_EQ(map.known_cells(), inside) << what;
  tree.prune();
}

struct Walk {
  const char* map;
  double resolution;
  ScanMapConfig model;
};

TEST(ScanMap, EveryCellEqualsOctomapsInsertPointCloud) {
  ScanMapConfig sharp;
  sharp.prob_hit = 0.9, sharp.prob_miss = 0.2, sharp.clamp_min = 0.05, sharp.clamp_max = 0.99;
  for (const Walk& w : {Walk{"maps/forest.yaml", 0.25, {}}, Walk{"maps/forest.yaml", 0.1, sharp},
                        Walk{"maps/valley.yaml", 0.4, {}}, Walk{"maps/valley.yaml", 0.25, sharp}}) {
    const auto arena = world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/" + w.map));
    const StaticRayScene scene(*arena);
    const Vec3 lo = arena->bounds().lo, hi = arena->bounds().hi;
    ScanMapConfig config = w.model;
    config.resolution = w.resolution;
    ScanMap map(config, lo, hi);
    octomap::OcTree tree(config.resolution);
    tree.setProbHit(config.prob_hit), tree.setProbMiss(config.prob_miss);
    tree.setClampingThresMin(config.clamp_min), tree.setClampingThresMax(config.clamp_max);
    LidarConfig lc;
    lc.azimuth_rays = 16, lc.elevation_rays = 4, lc.elevation_fov = 60.0, lc.range = 10.0;
    const Lidar lidar(lc);
    std::vector<Ray> rays(std::size_t(lidar.rays()));
    std::vector<RayHit> hits(rays.size());
    std::vector<Vec3> points(rays.size());
    Rng rng(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Vec3 at = lo + (hi - lo).cwiseProduct(Vec3(0.5, 0.5, 0.6));
    Heading h{0.0, kPi / 2};
    int echoes = 0, beyond = 0;
    for (int s = 0; s < 100; ++s) {
      // A random walk that stays inside the arena's middle.
      h.alpha += uniform(rng, -0.6, 0.6), h.theta = kPi / 2 + uniform(rng, -0.3, 0.3);
      at += 0.8 * direction(h);
      for (int d = 0; d < 3; ++d) at[d] = std::clamp(at[d], lo[d] + 0.3 * (hi[d] - lo[d]), hi[d] - 0.2 * (hi[d] - lo[d]));
      lidar.rays_at(at, h, rays);
      scene.cast(rays, lc.range, hits);
      octomap::Pointcloud cloud;
      for (std::size_t k = 0; k < rays.size(); ++k) {
        const bool echo = hits[k].target != RayTarget::kNone;
        // No echo: an endpoint beyond the range, which carves free space up to it; now and then exactly at it.
        const double d = echo ? hits[k].distance : (u(rng) < 0.1 ? lc.range : lc.range + 1.0);
        points[k] = at + d * rays[k].direction;
        cloud.push_back(float(points[k].x()), float(points[k].y()), float(points[k].z()));
        echoes += echo, beyond += !echo;
      }
      map.insert(at, points, lc.range);
      tree.insertPointCloud(cloud, octomap::point3d(float(at.x()), float(at.y()), float(at.z())), lc.range);
      if (s % 50 == 49) expect_same_cells(map, tree, lo, hi, w.map);
      if (::testing::Test::HasFailure()) return;
    }
    std::printf("%s at %.2f m: %lld known cells, %lld occupied; %d echoes, %d beyond range\n", w.map, w.resolution,
                map.known_cells(), map.occupied_cells(), echoes, beyond);
    EXPECT_GT(map.occupied_cells(), 50);
    EXPECT_GT(echoes, 1000);
    EXPECT_GT(beyond, 500);
  }
}

TEST(ScanMap, TheNearestOccupiedCellEqualsTestingEveryCell) {
  const auto arena = world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/maps/forest.yaml"));
  const StaticRayScene scene(*arena);
  const Vec3 lo = arena->bounds().lo, hi = arena->bounds().hi;
  Rng rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double resolution : {0.25, 0.15, 0.5}) {
    ScanMapConfig config;
    config.resolution = resolution;
    ScanMap map(config, lo, hi);
    EXPECT_FALSE(map.nearest_occupied(lo + 0.5 * (hi - lo), 100.0).found);
    LidarConfig lc;
    lc.azimuth_rays = 32, lc.elevation_rays = 4, lc.elevation_fov = 60.0, lc.range = 8.0;
    const Lidar lidar(lc);
    std::vector<Ray> rays(std::size_t(lidar.rays()));
    std::vector<RayHit> hits(rays.size());
    std::vector<Vec3> points(rays.size());
    int checked = 0, found = 0;
    for (int s = 0; s < 25; ++s) {
      const Vec3 at = lo + (hi - lo).cwiseProduct(Vec3(0.1 + 0.8 * u(rng), 0.1 + 0.8 * u(rng), 0.05 + 0.5 * u(rng)));
      lidar.rays_at(at, Heading{2 * kPi * u(rng), kPi / 2 + 0.3 * (u(rng) - 0.5)}, rays);
      scene.cast(rays, lc.range, hits);
      for (std::size_t k = 0; k < rays.size(); ++k) {
        points[k] = at + (hits[k].target != RayTarget::kNone ? hits[k].distance : lc.range + 1.0) * rays[k].direction;
      }
      map.insert(at, points, lc.range);
      std::vector<Vec3> occupied;
      map.for_each_known([&](const CellKey& key, float log_odds) {
        if (log_odds > 0.0f) occupied.push_back(map.centre(key));
      });
      // Queries near the scans, anywhere in the arena and a little outside it, with caps short and long.
      for (int q = 0; q < 40; ++q) {
        const Vec3 p = q % 2 == 0 ? Vec3(at + 3.0 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5))
                                  : Vec3(lo - Vec3::Constant(1.0) + (hi - lo + Vec3::Constant(2.0)).cwiseProduct(Vec3(u(rng), u(rng), u(rng))));
        const double cap = q % 3 == 0 ? 1.0 : q % 3 == 1 ? 5.0 : 60.0;
        double want = cap;
        bool want_found = false;
        for (const Vec3& c : occupied) {
          const Vec3 h = Vec3::Constant(0.5 * resolution);
          const double d = (p.cwiseMax(c - h).cwiseMin(c + h) - p).norm();
          if (d <= cap && (!want_found || d < want)) want = d, want_found = true;
        }
        const OccupiedPoint got = map.nearest_occupied(p, cap);
        ASSERT_EQ(got.found, want_found) << "query " << q << " at scan " << s;
        ASSERT_NEAR(got.distance, want, 1e-12) << "query " << q << " at scan " << s;
        if (got.found) {
          // The point lies on an occupied cell's cube at that distance.
          const CellKey k = map.key_of(got.point + 1e-9 * (got.point - p).normalized());
          EXPECT_NEAR((got.point - p).norm(), got.distance, 1e-12);
          if (got.distance > 1e-6) {
            EXPECT_GT(map.log_odds(k), 0.0f) << "query " << q;
          }
        }
        ++checked, found += got.found;
      }
    }
    std::printf("at %.2f m: %d queries, %d found; %lld occupied cells\n", resolution, checked, found, map.occupied_cells());
    EXPECT_GT(found, checked / 3);
    EXPECT_LT(found, checked);
  }
}

TEST(ScanMap, WithUnknownCellsAsObstaclesTheNearestEqualsTestingEveryCell) {
  // unknown_is_occupied: every cell of the box no scan has touched counts, as well as the occupied ones. Random
  // scans in a box whose grid ends inside its last bricks (cells beyond it count as nothing); each query's answer
  // equals testing every cell of the box, held bricks and bricks not held alike.
  const Vec3 lo(0.3, -1.1, 0.2), hi(13.7, 9.9, 6.6);
  ScanMapConfig c;
  c.resolution = 0.3;
  c.unknown_is_occupied = true;
  ScanMap map(c, lo, hi);
  Rng rng(8);
  const CellKey k0 = map.key_of(lo), k1 = map.key_of(hi);
  int checked = 0, at_unknown = 0, at_occupied = 0;
  for (int s = 0; s < 12; ++s) {
    const Vec3 o = lo + (hi - lo).cwiseProduct(Vec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1)));
    std::vector<Vec3> points;
    for (int k = 0; k < 60; ++k) points.push_back(o + Vec3(uniform(rng, -8, 8), uniform(rng, -8, 8), uniform(rng, -4, 4)));
    map.insert(o, points, 6.0);
    std::vector<std::pair<Vec3, bool>> blocked;  // centre, unknown
    for (int x = k0[0]; x <= k1[0]; ++x) {
      for (int y = k0[1]; y <= k1[1]; ++y) {
        for (int z = k0[2]; z <= k1[2]; ++z) {
          const CellKey key{std::uint16_t(x), std::uint16_t(y), std::uint16_t(z)};
          const float v = map.log_odds(key);
          if (v != v || v > 0.0f) blocked.emplace_back(map.centre(key), v != v);
        }
      }
    }
    std::vector<Vec3> ends;  // the endpoints within range: their cells are occupied
    for (const Vec3& e : points) {
      if ((e - o).norm() < 5.9) ends.push_back(e);
    }
    for (int q = 0; q < 25; ++q) {
      const Vec3 p = q % 3 == 0 && !ends.empty() ? ends[std::size_t(q) % ends.size()]
                                                 : Vec3(o + Vec3(uniform(rng, -4, 4), uniform(rng, -4, 4), uniform(rng, -2, 2)));
      const double cap = q % 2 == 0 ? 1.5 : 6.0;
      double want = cap;
      bool want_found = false, want_unknown = false;
      for (const auto& [centre, unknown] : blocked) {
        const Vec3 h = Vec3::Constant(0.5 * c.resolution);
        const double d = (p.cwiseMax(centre - h).cwiseMin(centre + h) - p).norm();
        if (d <= cap && (!want_found || d < want)) want = d, want_found = true, want_unknown = unknown;
      }
      const OccupiedPoint got = map.nearest_occupied(p, cap);
      ASSERT_EQ(got.found, want_found) << "query " << q << " at scan " << s;
      ASSERT_NEAR(got.distance, want, 1e-12) << "query " << q << " at scan " << s;
      ++checked;
      if (want_found) (want_unknown ? at_unknown : at_occupied) += 1;
    }
  }
  std::printf("%d queries: %d nearest at an unknown cell, %d at an occupied one\n", checked, at_unknown, at_occupied);
  EXPECT_GT(at_unknown, 20);
  EXPECT_GT(at_occupied, 5);
}

TEST(ScanMap, ARayBeyondRangeCarvesFreeSpaceOnlyAndAnEndpointWinsOverFree) {
  ScanMapConfig c;
  c.resolution = 0.5;
  ScanMap map(c, Vec3::Zero(), Vec3(20, 20, 20));
  const Vec3 o(1.1, 5.2, 5.3);
  // Along +x: an echo at 4 m, and a ray beyond its 6 m range.
  map.insert(o, std::vector<Vec3>{o + Vec3(4.0, 0, 0)}, 6.0);
  const float hit = std::log(0.7f / 0.3f), miss = std::log(0.4f / 0.6f);
  EXPECT_NEAR(map.log_odds(map.key_of(o + Vec3(4.0, 0, 0))), hit, 1e-6);
  EXPECT_NEAR(map.log_odds(map.key_of(o + Vec3(2.0, 0, 0))), miss, 1e-6);
  EXPECT_TRUE(std::isnan(map.log_odds(map.key_of(o + Vec3(4.6, 0, 0)))));
  ScanMap far(c, Vec3::Zero(), Vec3(20, 20, 20));
  far.insert(o, std::vector<Vec3>{o + Vec3(9.0, 0, 0)}, 6.0);
  EXPECT_NEAR(far.log_odds(far.key_of(o + Vec3(5.6, 0, 0))), miss, 1e-6);
  EXPECT_TRUE(std::isnan(far.log_odds(far.key_of(o + Vec3(6.6, 0, 0)))));
  EXPECT_EQ(far.occupied_cells(), 0);
  // Two rays of one scan: one ends in a cell the other crosses; the cell is occupied, once.
  ScanMap both(c, Vec3::Zero(), Vec3(20, 20, 20));
  both.insert(o, std::vector<Vec3>{o + Vec3(2.0, 0, 0), o + Vec3(4.0, 0, 0)}, 6.0);
  EXPECT_NEAR(both.log_odds(both.key_of(o + Vec3(2.0, 0, 0))), hit, 1e-6);
  // Repeated scans clamp.
  for (int k = 0; k < 20; ++k) both.insert(o, std::vector<Vec3>{o + Vec3(4.0, 0, 0)}, 6.0);
  EXPECT_EQ(both.log_odds(both.key_of(o + Vec3(4.0, 0, 0))), float(std::log(0.971 / 0.029)));
  EXPECT_EQ(both.log_odds(both.key_of(o + Vec3(1.0, 0, 0))), float(std::log(0.1192 / 0.8808)));
  both.clear();
  EXPECT_EQ(both.known_cells(), 0);
  EXPECT_TRUE(std::isnan(both.log_odds(both.key_of(o + Vec3(4.0, 0, 0)))));
}

TEST(ScanMap, AClearedMapIsANewMapAndSaysWhenAScanMovedItsObstacles) {
  // Random scans in a box whose grid ends inside its last bricks (kOutside cells), cleared, scanned again: every
  // cell and every nearest answer equals a new map's fed the second scans, for both readings of unknown cells.
  const Vec3 lo(0.3, -1.1, 0.2), hi(13.7, 9.9, 6.6);
  for (const bool unknown_blocks : {false, true}) {
    SCOPED_TRACE(unknown_blocks ? "unknown is occupied" : "unknown is free");
    ScanMapConfig c;
    c.resolution = 0.3;
    c.unknown_is_occupied = unknown_blocks;
    ScanMap used(c, lo, hi);
    Rng rng(unknown_blocks ? 5 : 4);
    const auto scan = [&](int n) {
      const Vec3 o = lo + (hi - lo).cwiseProduct(Vec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1)));
      std::vector<Vec3> points;
      for (int k = 0; k < n; ++k) points.push_back(o + Vec3(uniform(rng, -8, 8), uniform(rng, -8, 8), uniform(rng, -4, 4)));
      return std::pair{o, points};
    };
    for (int s = 0; s < 40; ++s) {
      const auto [o, points] = scan(30);
      used.insert(o, points, 6.0);
    }
    ASSERT_GT(used.known_cells(), 1000);
    used.clear();
    EXPECT_EQ(used.known_cells(), 0);
    EXPECT_EQ(used.occupied_cells(), 0);
    EXPECT_FALSE(used.last_insert_moved_obstacles());
    ScanMap fresh(c, lo, hi);
    int moved = 0, still = 0, within = 0;
    for (int s = 0; s < 10; ++s) {
      const auto [o, points] = scan(s % 3 == 2 ? 0 : 20);  // some scans with no ray at all
      const auto before = fresh.nearest_occupied(o, 3.0);
      std::vector<Vec3> queries;  // and points about it, each with its answer before the insert
      std::vector<double> was;
      for (int q = 0; q < 50; ++q) {
        queries.push_back(o + Vec3(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -3, 3)));
        was.push_back(fresh.nearest_occupied(queries.back(), 3.0).distance);
      }
      used.insert(o, points, 6.0);
      fresh.insert(o, points, 6.0);
      EXPECT_EQ(used.last_insert_moved_obstacles(), fresh.last_insert_moved_obstacles());
      const auto after = fresh.nearest_occupied(o, 3.0);
      if (!fresh.last_insert_moved_obstacles()) {
        EXPECT_EQ(after.distance, before.distance);  // nothing nearest_occupied counts changed
        ++still;
      } else {
        ++moved;
      }
      for (std::size_t q = 0; q < queries.size(); ++q) {
        const bool near = fresh.last_insert_moved_obstacles_within(queries[q], was[q]);
        EXPECT_EQ(near, used.last_insert_moved_obstacles_within(queries[q], was[q]));
        if (!near) {
          EXPECT_EQ(fresh.nearest_occupied(queries[q], 3.0).distance, was[q]) << "query " << q;
        }
        within += near;
      }
    }
    EXPECT_GT(moved, 0);
    EXPECT_GT(still, 0);
    EXPECT_GT(within, 0);
    EXPECT_LT(within, 500);  // some queries lay beyond every changed cell
    std::vector<std::pair<CellKey, float>> a, b;
    used.for_each_known([&](const CellKey& k, float v) { a.emplace_back(k, v); });
    fresh.for_each_known([&](const CellKey& k, float v) { b.emplace_back(k, v); });
    EXPECT_EQ(a, b);
    EXPECT_EQ(used.known_cells(), fresh.known_cells());
    EXPECT_EQ(used.occupied_cells(), fresh.occupied_cells());
    for (int q = 0; q < 300; ++q) {
      const Vec3 p = lo + (hi - lo).cwiseProduct(Vec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1)));
      const OccupiedPoint x = used.nearest_occupied(p, 4.0), y = fresh.nearest_occupied(p, 4.0);
      ASSERT_EQ(x.found, y.found) << q;
      ASSERT_EQ(x.distance, y.distance) << q;
    }
  }
}

TEST(ScanMap, ASavedMapReadsBackWithOctomapAsTheCellsTheScansMade) {
  const auto arena = world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/maps/forest.yaml"));
  const StaticRayScene scene(*arena);
  const Vec3 lo = arena->bounds().lo, hi = arena->bounds().hi;
  ScanMap map(ScanMapConfig{}, lo, hi);
  LidarConfig lc;
  lc.azimuth_rays = 32, lc.elevation_rays = 4, lc.elevation_fov = 60.0, lc.range = 8.0;
  const Lidar lidar(lc);
  std::vector<Ray> rays(std::size_t(lidar.rays()));
  std::vector<RayHit> hits(rays.size());
  std::vector<Vec3> points(rays.size());
  Rng rng(31);
  for (int s = 0; s < 30; ++s) {
    const Vec3 at = lo + (hi - lo).cwiseProduct(Vec3(uniform(rng, 0.1, 0.9), uniform(rng, 0.1, 0.9), uniform(rng, 0.05, 0.5)));
    lidar.rays_at(at, Heading{uniform(rng, -kPi, kPi), kPi / 2}, rays);
    scene.cast(rays, lc.range, hits);
    for (std::size_t k = 0; k < rays.size(); ++k) {
      points[k] = at + (hits[k].target != RayTarget::kNone ? hits[k].distance : lc.range + 1.0) * rays[k].direction;
    }
    map.insert(at, points, lc.range);
  }
  const auto file = std::filesystem::temp_directory_path() / "peg3d_scan_map_test.bt";
  map.write_bt(file);
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(file.string()));
  EXPECT_EQ(tree.getResolution(), 0.25);
  // Binary files keep occupied or free: every known cell reads back as the scans left it, and nothing else is known.
  long long known = 0, occupied = 0, wrong = 0;
  map.for_each_known([&](const CellKey& k, float log_odds) {
    const octomap::OcTreeNode* n = tree.search(octomap::OcTreeKey(k[0], k[1], k[2]));
    ++known, occupied += log_odds > 0.0f;
    if (n == nullptr || tree.isNodeOccupied(n) != (log_odds > 0.0f)) ++wrong;
  });
  EXPECT_EQ(wrong, 0);
  tree.expand();
  long long leaves = 0, tree_occupied = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) ++leaves, tree_occupied += tree.isNodeOccupied(*it);
  EXPECT_EQ(leaves, known);
  EXPECT_EQ(tree_occupied, occupied);
  EXPECT_GT(occupied, 100);
  std::filesystem::remove(file);
  EXPECT_THROW(map.write_bt("/nonexistent-dir/map.bt"), std::runtime_error);
}

TEST(ScanMap, ABoxTooFineForItsTablesIsRefused) {
  ScanMapConfig c;
  c.resolution = 0.02;  // 2.5e11 cells: more than 2^36
  EXPECT_THROW(ScanMap(c, Vec3::Zero(), Vec3(1000, 1000, 100)), InvalidParameter);
  c.resolution = 0.25;
  const ScanMap paper(c, Vec3::Zero(), Vec3(35, 35, 20));
  std::printf("paper arena at 0.25 m, no scan yet: %zu bytes\n", paper.bytes());
  EXPECT_LT(paper.bytes(), 28u << 10);  // 5 x 5 x 3 chunks, and a byte for each of its 36 x 36 x 21 bricks
}

// Scans from points about one place, in every direction and along the axes and diagonals, now and then from a
// cell's corner or centre (where the traversal's ties between axes fall): the cells about it are met by many rays
// and reach the lower clamp, and every cell equals OctoMap's.
TEST(ScanMap, RaysAlongAxesAndDiagonalsFromCornersMeetOctomapsCells) {
  for (const double resolution : {0.25, 0.1, 0.4}) {
    SCOPED_TRACE(resolution);
    ScanMapConfig c;
    c.resolution = resolution;
    const Vec3 lo(-3.3, -2.2, -1.1), hi(9.9, 11.1, 6.6);
    ScanMap map(c, lo, hi);
    octomap::OcTree tree(resolution);
    Rng rng(std::uint64_t(resolution * 1000));
    std::vector<Vec3> directions;
    for (int x = -1; x <= 1; ++x) {
      for (int y = -1; y <= 1; ++y) {
        for (int z = -1; z <= 1; ++z) {
          if (x != 0 || y != 0 || z != 0) directions.push_back(Vec3(x, y, z).normalized());
        }
      }
    }
    const Vec3 middle(3.1, 4.4, 2.7);
    for (int s = 0; s < 160; ++s) {
      // Now and then from a cell's corner or centre, where the traversal's ties between axes fall.
      Vec3 o = middle + Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -0.5, 0.5));
      if (s % 4 == 1) o = (o / resolution).array().round().matrix() * resolution;
      if (s % 4 == 3) o = ((o / resolution).array().floor() + 0.5).matrix() * resolution;
      std::vector<Vec3> points;
      octomap::Pointcloud cloud;
      for (int k = 0; k < 60; ++k) {
        const Vec3 d = k < int(directions.size())
                           ? directions[std::size_t(k)]
                           : Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)).normalized();
        const double range = k % 5 == 0 ? 7.5 : uniform(rng, 1.0, 7.0);  // some beyond the 6 m max range
        points.push_back(o + range * d);
        cloud.push_back(float(points.back().x()), float(points.back().y()), float(points.back().z()));
      }
      map.insert(o, points, 6.0);
      tree.insertPointCloud(cloud, octomap::point3d(float(o.x()), float(o.y()), float(o.z())), 6.0);
      if (s % 40 == 39) expect_same_cells(map, tree, lo, hi, "about one place");
      if (::testing::Test::HasFailure()) return;
    }
  }
}

// A map holds the bricks its scans reached and no other: a 1 km x 1 km x 100 m box at 0.25 m (6.4e9 cells) takes
// its chunk table, then grows with the walk; clear() keeps the memory, so the same scans again allocate nothing.
TEST(ScanMap, AMapHoldsTheBricksItsScansReached) {
  const Vec3 lo(-500, -500, 0), hi(500, 500, 100);
  ScanMapConfig c;
  ScanMap map(c, lo, hi);
  EXPECT_LT(map.bytes(), 1u << 20);
  Rng rng(9);
  std::vector<std::pair<Vec3, std::vector<Vec3>>> scans;
  Vec3 at(0, 0, 3);
  for (int s = 0; s < 200; ++s) {
    at += Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), 0.0);
    std::vector<Vec3> points;
    for (int k = 0; k < 64; ++k) {
      const double a = 2 * kPi * k / 64.0, e = uniform(rng, -0.4, 0.4);
      points.push_back(at + uniform(rng, 2, 12) * Vec3(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e)));
    }
    scans.emplace_back(at, points);
  }
  for (const auto& [o, points] : scans) map.insert(o, points, 10.0);
  std::set<std::array<int, 3>> bricks;
  const CellKey k0 = map.key_of(lo);
  map.for_each_known([&](const CellKey& k, float) { bricks.insert({(k[0] - k0[0]) / 4, (k[1] - k0[1]) / 4, (k[2] - k0[2]) / 4}); });
  EXPECT_EQ(map.held_bricks(), bricks.size());
  std::printf("1 km box: %zu bricks held after %zu scans, %.1f MB\n", map.held_bricks(), scans.size(), double(map.bytes()) / 1e6);
  EXPECT_LT(map.bytes(), 50u << 20);
  // Resident memory follows the bricks: tables and lists aside, at most twice the bricks' own bytes.
  EXPECT_LT(double(map.bytes()), 2.0 * double(map.held_bricks()) * 300.0 + (4u << 20));
  // Nearest occupied cells in a box of more bricks than get a byte each (there the chunks' counts pass the empty
  // ones) equal testing every occupied cell, before and after a clear().
  const auto expect_nearest = [&] {
    std::vector<Vec3> occupied;
    map.for_each_known([&](const CellKey& k, float v) {
      if (v > 0.0f) occupied.push_back(map.centre(k));
    });
    ASSERT_GT(occupied.size(), 100u);
    Rng q(11);
    const Vec3 half = Vec3::Constant(0.5 * c.resolution);
    int found = 0;
    for (int i = 0; i < 100; ++i) {
      const Vec3 p = scans[std::size_t(2 * i)].first + Vec3(uniform(q, -20, 20), uniform(q, -20, 20), uniform(q, -3, 3));
      double want = 3.0;
      for (const Vec3& cell : occupied) want = std::min(want, (p.cwiseMax(cell - half).cwiseMin(cell + half) - p).norm());
      const OccupiedPoint got = map.nearest_occupied(p, 3.0);
      ASSERT_EQ(got.found, want < 3.0) << i;
      ASSERT_NEAR(got.distance, want, 1e-12) << i;
      found += got.found;
    }
    EXPECT_GT(found, 10);
    EXPECT_LT(found, 100);
  };
  expect_nearest();
  const long long grown = map.allocations();
  const auto known = map.known_cells();
  map.clear();
  EXPECT_EQ(map.held_bricks(), 0u);
  EXPECT_FALSE(map.nearest_occupied(scans.front().first, 3.0).found);
  for (const auto& [o, points] : scans) map.insert(o, points, 10.0);
  EXPECT_EQ(map.allocations(), grown);
  EXPECT_EQ(map.known_cells(), known);
  expect_nearest();
}

TEST(ScanMap, OctoMapsKeysReachAnArenaWithin32768CellsOfTheOriginAndNoFurther) {
  ScanMapConfig c;
  c.resolution = 0.25;  // keys -32768 .. 32767: [-8192, 8192) m
  EXPECT_TRUE(ScanMap::keys_reach(c, Vec3(0, 0, 0), Vec3(35, 35, 20)));
  EXPECT_TRUE(ScanMap::keys_reach(c, Vec3(-8192.0, -8192.0, 0), Vec3(8191.99, 10, 10)));
  EXPECT_FALSE(ScanMap::keys_reach(c, Vec3(8180, 0, 0), Vec3(8192.0, 10, 10)));    // straddles the last key
  EXPECT_FALSE(ScanMap::keys_reach(c, Vec3(-8192.01, 0, 0), Vec3(0, 10, 10)));
  EXPECT_FALSE(ScanMap::keys_reach(c, Vec3(0, 0, 9000), Vec3(10, 10, 9020)));      // any axis
  c.resolution = 1.0;  // four times as far
  EXPECT_TRUE(ScanMap::keys_reach(c, Vec3(9000, 0, 0), Vec3(9020, 20, 10)));
  EXPECT_THROW(ScanMap(ScanMapConfig{}, Vec3(9000, 0, 0), Vec3(9020, 20, 10)), InvalidParameter);
}

}  // namespace
}  // namespace peg3d::sense
