// The collision world: agents driven into each kind of obstacle collide at the right time and place, pass
// safely otherwise, never tunnel through thin walls or ridges in one long step, never collide with each
// other, and the distance-field early-out never changes an answer.

#include <array>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <latch>
#include <thread>
#include <vector>

#include "world/collision/collision_world.hpp"
#include "world/map/map_loader.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

using testing::empty_spec;

// Bullet's time of impact stops within 1 mm of contact, and the agent is set back 1 mm more.
constexpr double kPlaceTolerance = 2.5e-3;  // m
constexpr double kPointTolerance = 2e-3;    // m

std::shared_ptr<const Arena> arena_with(MapSpec spec) { return testing::build(spec); }

/// The fraction along from -> to at which the agent's centre reaches `contact_centre`.
double fraction_at(const Vec3& from, const Vec3& to, const Vec3& contact_centre) {
  return (contact_centre - from).norm() / (to - from).norm();
}

void expect_hit(CollisionWorld& world, int agent, const Vec3& from, const Vec3& to, ObstacleKind kind, int id,
                const Vec3& contact_centre, const Vec3& point, const Vec3& normal) {
  world.place_agent(agent, from);
  const auto c = world.move_agent(agent, to);
  ASSERT_TRUE(c.has_value()) << "no contact moving " << from.transpose() << " -> " << to.transpose();
  EXPECT_EQ(c->agent, agent);
  EXPECT_EQ(c->kind, kind);
  EXPECT_EQ(c->obstacle_id, id);
  const double length = (to - from).norm();
  EXPECT_NEAR(c->fraction, fraction_at(from, to, contact_centre), kPlaceTolerance / length);
  EXPECT_LE(c->fraction, fraction_at(from, to, contact_centre) + 1e-9);  // never past the contact
  EXPECT_LT((c->point - point).norm(), kPointTolerance) << c->point.transpose() << " vs " << point.transpose();
  EXPECT_GT(c->normal.dot(normal), 0.999) << c->normal.transpose();
  EXPECT_EQ(c->penetration, 0.0);
  // Stopped a hair before the contact, outside the obstacle.
  const Vec3 at = world.agent_position(agent);
  EXPECT_LT((at - contact_centre).norm(), kPlaceTolerance) << at.transpose();
  EXPECT_LE((at - from).norm(), (contact_centre - from).norm() + 1e-12);
  EXPECT_FALSE(world.overlap(agent).has_value());
}

TEST(WorldCollision, AgentHitsASphere) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.2);
  spec.spheres.push_back({Vec3(7, 7, 7), 0.5});  // id 0, a decoy
  spec.spheres.push_back({Vec3(5, 5, 5), 1.0});  // id 1
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.5);
  expect_hit(world, a, Vec3(1, 5, 5), Vec3(9, 5, 5), ObstacleKind::kSphere, 1, Vec3(3.5, 5, 5), Vec3(4, 5, 5),
             Vec3(-1, 0, 0));
  // An oblique approach: contact where the centres are 1.5 m apart.
  const Vec3 from(1, 4.2, 5), to(9, 4.2, 5);
  const double x = 5 - std::sqrt(1.5 * 1.5 - 0.8 * 0.8);
  const Vec3 centre(x, 4.2, 5);
  expect_hit(world, a, from, to, ObstacleKind::kSphere, 1, centre, Vec3(5, 5, 5) + (centre - Vec3(5, 5, 5)) / 1.5,
             (centre - Vec3(5, 5, 5)).normalized());
}

TEST(WorldCollision, AgentHitsACylinderSideAndTop) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.2);
  spec.cylinders.push_back({Vec3(5, 5, 0), 1.0, 6.0});
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.25);
  expect_hit(world, a, Vec3(5, 1, 3), Vec3(5, 9, 3), ObstacleKind::kCylinder, 0, Vec3(5, 3.75, 3), Vec3(5, 4, 3),
             Vec3(0, -1, 0));
  expect_hit(world, a, Vec3(5.3, 4.8, 9), Vec3(5.3, 4.8, 2), ObstacleKind::kCylinder, 0, Vec3(5.3, 4.8, 6.25),
             Vec3(5.3, 4.8, 6), Vec3(0, 0, 1));
}

TEST(WorldCollision, AgentHitsATerrainMesh) {
  MapSpec spec = empty_spec(Vec3(20, 10, 8), 0.2);
  spec.meshes.push_back(testing::mesh_entry("ridge.obj"));
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.5);
  // Straight down onto the flat part.
  expect_hit(world, a, Vec3(3, 5, 6), Vec3(3, 5, -1), ObstacleKind::kMesh, 0, Vec3(3, 5, 0.5), Vec3(3, 5, 0),
             Vec3(0, 0, 1));
  // Level flight into the ridge's slope z = x - 6: the centre touches when x = 9 - r sqrt(2).
  const double r = 0.5, x = 9 - r * std::sqrt(2.0);
  const Vec3 n = Vec3(-1, 0, 1).normalized();
  expect_hit(world, a, Vec3(2, 5, 3), Vec3(9, 5, 3), ObstacleKind::kMesh, 0, Vec3(x, 5, 3), Vec3(x, 5, 3) - r * n, n);
}

TEST(WorldCollision, SafePassDoesNotCollide) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.2);
  spec.spheres.push_back({Vec3(5, 5, 5), 1.0});
  spec.cylinders.push_back({Vec3(2, 8, 0), 0.5, 9.0});
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.5);
  // Past the sphere 1 cm clear of its surface, and along the cylinder 2 cm clear.
  world.place_agent(a, Vec3(1, 5 - 1.51, 5));
  EXPECT_FALSE(world.move_agent(a, Vec3(9, 5 - 1.51, 5)).has_value());
  EXPECT_EQ(world.agent_position(a), Vec3(9, 5 - 1.51, 5));
  world.place_agent(a, Vec3(2 + 1.02, 8, 1));
  EXPECT_FALSE(world.move_agent(a, Vec3(2 + 1.02, 8, 8.5)).has_value());
  EXPECT_FALSE(world.overlap(a).has_value());
}

TEST(WorldCollision, LongStepsCannotTunnel) {
  MapSpec spec = empty_spec(Vec3(20, 20, 12), 0.25);
  spec.meshes.push_back(testing::mesh_entry("wall.obj", Vec3(10, 10, 0)));   // zero thickness at x = 10
  spec.cylinders.push_back({Vec3(10, 3, 5.0), 2.0, 0.01});                 // a 1 cm disc
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.1);
  // One 18 m step straight through the wall.
  expect_hit(world, a, Vec3(1, 10, 5), Vec3(19, 10, 5), ObstacleKind::kMesh, 0, Vec3(9.9, 10, 5), Vec3(10, 10, 5),
             Vec3(-1, 0, 0));
  // From behind, the other way.
  expect_hit(world, a, Vec3(19, 12, 3), Vec3(1, 12, 3), ObstacleKind::kMesh, 0, Vec3(10.1, 12, 3), Vec3(10, 12, 3),
             Vec3(1, 0, 0));
  // A 10 m drop through the thin disc.
  expect_hit(world, a, Vec3(10.5, 3, 11), Vec3(10.5, 3, 1), ObstacleKind::kCylinder, 0, Vec3(10.5, 3, 5.11),
             Vec3(10.5, 3, 5.01), Vec3(0, 0, 1));
}

TEST(WorldCollision, LongStepCannotCrossARidge) {
  MapSpec spec = empty_spec(Vec3(20, 10, 8), 0.2);
  spec.meshes.push_back(testing::mesh_entry("ridge.obj"));
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.3);
  // 16 m in one step at z = 3, below the ridge top (z = 4): stopped on the near slope.
  const double r = 0.3, x = 9 - r * std::sqrt(2.0);
  const Vec3 n = Vec3(-1, 0, 1).normalized();
  expect_hit(world, a, Vec3(2, 5, 3), Vec3(18, 5, 3), ObstacleKind::kMesh, 0, Vec3(x, 5, 3), Vec3(x, 5, 3) - r * n, n);
  // Just above the ridge's edge (top at z = 4) the same step goes through.
  world.place_agent(a, Vec3(2, 5, 4 + r * std::sqrt(2.0) + 0.01));
  EXPECT_FALSE(world.move_agent(a, Vec3(18, 5, 4 + r * std::sqrt(2.0) + 0.01)).has_value());
}

TEST(WorldCollision, AgentsDoNotCollideWithEachOther) {
  CollisionWorld world(arena_with(empty_spec(Vec3::Constant(10), 0.25)));
  const int a = world.add_agent(0.5), b = world.add_agent(0.5);
  EXPECT_EQ(a, 0);
  EXPECT_EQ(b, 1);
  world.place_agent(a, Vec3(5, 5, 5));
  world.place_agent(b, Vec3(5.2, 5, 5));
  EXPECT_FALSE(world.overlap(a).has_value());
  EXPECT_FALSE(world.move_agent(b, Vec3(2, 5, 5)).has_value());
  EXPECT_FALSE(world.move_agent(a, Vec3(1, 5, 5)).has_value());
  EXPECT_EQ(world.agent_position(a), Vec3(1, 5, 5));
}

TEST(WorldCollision, OverlapReportsPenetrationAndBlocksMovingDeeper) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.2);
  spec.spheres.push_back({Vec3(5, 5, 5), 1.0});
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.5);
  world.place_agent(a, Vec3(3.7, 5, 5));  // centres 1.3 m apart: 0.2 m deep
  const auto o = world.overlap(a);
  ASSERT_TRUE(o.has_value());
  EXPECT_EQ(o->kind, ObstacleKind::kSphere);
  EXPECT_NEAR(o->penetration, 0.2, 1e-6);
  EXPECT_TRUE(o->normal.isApprox(Vec3(-1, 0, 0), 1e-6));
  EXPECT_NEAR((o->point - Vec3(4, 5, 5)).norm(), 0.0, 1e-6);
  // Deeper: stopped where it stands, with the penetration.
  const auto c = world.move_agent(a, Vec3(4.5, 5, 5));
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->fraction, 0.0);
  EXPECT_NEAR(c->penetration, 0.2, 1e-6);
  EXPECT_EQ(world.agent_position(a), Vec3(3.7, 5, 5));
  // Out: free.
  EXPECT_FALSE(world.move_agent(a, Vec3(2, 5, 5)).has_value());
  EXPECT_FALSE(world.overlap(a).has_value());
}

TEST(WorldCollision, StoppedAgentStaysOutside) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.2);
  spec.spheres.push_back({Vec3(5, 5, 5), 1.0});
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.5);
  world.place_agent(a, Vec3(1, 5.3, 5));
  ASSERT_TRUE(world.move_agent(a, Vec3(8, 5.3, 5)).has_value());
  const Vec3 stopped = world.agent_position(a);
  // Pushing on keeps it in place; it never ends inside.
  for (int i = 0; i < 5; ++i) {
    const auto c = world.move_agent(a, stopped + Vec3(1, 0, 0));
    ASSERT_TRUE(c.has_value());
    EXPECT_FALSE(world.overlap(a).has_value());
  }
  EXPECT_LT((world.agent_position(a) - stopped).norm(), kPlaceTolerance);
  // Sliding away along the surface is allowed.
  EXPECT_FALSE(world.move_agent(a, world.agent_position(a) + Vec3(0, 2, 0)).has_value());
}

TEST(WorldCollision, ObstaclesNearAPointAreTheExactNearestPointsNearestFirst) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.2);
  spec.spheres.push_back({Vec3(7, 7, 7), 0.5});  // id 0, out of range
  spec.spheres.push_back({Vec3(5, 3, 5), 1.0});  // id 1
  spec.cylinders.push_back({Vec3(2, 2, 0), 0.5, 6.0});
  CollisionWorld world(arena_with(spec));
  std::array<NearPoint, 4> near;
  // sqrt(3.25) - 1 m from the sphere's surface, 1.0 m from the cylinder's side; the decoy is 5.6 m away.
  const Vec3 p(3.5, 2, 5), centre(5, 3, 5);
  const double to_sphere = (p - centre).norm();
  const int n = world.obstacles_near(p, 2.0, near);
  ASSERT_EQ(n, 2);
  EXPECT_EQ(near[0].kind, ObstacleKind::kSphere);
  EXPECT_EQ(near[0].obstacle_id, 1);
  EXPECT_EQ(near[0].triangle, -1);
  EXPECT_NEAR(near[0].distance, to_sphere - 1.0, 1e-6);
  EXPECT_LT((near[0].point - (centre + (p - centre) / to_sphere)).norm(), 1e-6);
  EXPECT_EQ(near[1].kind, ObstacleKind::kCylinder);
  EXPECT_EQ(near[1].obstacle_id, 0);
  EXPECT_NEAR(near[1].distance, 1.0, 1e-6);
  EXPECT_LT((near[1].point - Vec3(2.5, 2, 5)).norm(), 1e-6);
  // A shorter range leaves the cylinder out; a buffer of one keeps the nearest.
  EXPECT_EQ(world.obstacles_near(p, 0.9, near), 1);
  EXPECT_EQ(world.obstacles_near(p, 2.0, std::span(near).first(1)), 1);
  EXPECT_EQ(near[0].kind, ObstacleKind::kSphere);
  // Over the cylinder's top the nearest point is on the top disc.
  ASSERT_EQ(world.obstacles_near(Vec3(2.2, 1.9, 6.4), 0.5, near), 1);
  EXPECT_NEAR(near[0].distance, 0.4, 1e-6);
  EXPECT_LT((near[0].point - Vec3(2.2, 1.9, 6.0)).norm(), 1e-6);
  EXPECT_EQ(world.obstacles_near(Vec3(8, 2, 2), 1.0, near), 0);
}

TEST(WorldCollision, ObstaclesNearAPointInAMeshCreaseAreEachSideOfIt) {
  // The ridge's valley at x = 6: the flat strip z = 0 and the slope z = x - 6 meet there.
  MapSpec spec = empty_spec(Vec3(20, 10, 8), 0.2);
  spec.meshes.push_back(testing::mesh_entry("ridge.obj"));
  CollisionWorld world(arena_with(spec));
  std::array<NearPoint, 8> near;
  const Vec3 p(6.2, 5, 0.5);
  const int n = world.obstacles_near(p, 0.6, near);
  ASSERT_GE(n, 2);
  // The slope first: (x - z - 6) / sqrt(2) = -0.3 / sqrt(2) from its plane, the foot inside the triangle.
  EXPECT_EQ(near[0].kind, ObstacleKind::kMesh);
  EXPECT_GE(near[0].triangle, 0);
  EXPECT_NEAR(near[0].distance, 0.3 / std::sqrt(2.0), 1e-6);
  EXPECT_LT((near[0].point - Vec3(6.35, 5, 0.35)).norm(), 1e-6);
  // And the flat strip, whose nearest point is on the crease.
  bool flat = false;
  for (int i = 0; i < n; ++i) {
    EXPECT_LT(near[std::size_t(i)].distance, 0.6);
    if (i > 0) {
      EXPECT_GE(near[std::size_t(i)].distance, near[std::size_t(i - 1)].distance);
    }
    flat |= std::abs(near[std::size_t(i)].distance - std::sqrt(0.04 + 0.25)) < 1e-6;
  }
  EXPECT_TRUE(flat);
}

TEST(WorldCollision, ArenaFacesAreNotCollisions) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.2);
  spec.floor_is_obstacle = spec.walls_is_obstacle = spec.ceiling_is_obstacle = true;
  CollisionWorld world(arena_with(spec));
  const int a = world.add_agent(0.5);
  world.place_agent(a, Vec3(5, 5, 1));
  EXPECT_FALSE(world.move_agent(a, Vec3(5, 5, -3)).has_value());  // the game clamps to the box, not Bullet
}

TEST(WorldCollision, EarlyOutNeverChangesAnAnswer) {
  // Every kind of obstacle, faces as obstacles (they only make the field more cautious), random moves of all
  // lengths: a world using the distance field to skip sweeps must agree exactly with one that always sweeps.
  MapSpec spec = load_map(testing::source_dir() / "maps" / "paper.yaml");
  spec.cylinders.push_back({Vec3(17.5, 17.5, 0), 1.5, 12});
  spec.cylinders.push_back({Vec3(25, 10, 8), 0.8, 0.05});
  spec.meshes.push_back(testing::mesh_entry("ridge.obj", Vec3(5, 12, 0)));
  spec.meshes.push_back(testing::mesh_entry("wall.obj", Vec3(12, 25, 4), 0.8));
  const auto arena = arena_with(spec);
  CollisionWorld fast(arena), exact(arena, CollisionOptions{false});
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double radii[2] = {0.25, 0.6};
  for (int k = 0; k < 2; ++k) {
    fast.add_agent(radii[k]);
    exact.add_agent(radii[k]);
  }
  const Box inside = arena->bounds();
  auto random_point = [&]() -> Vec3 { return inside.lo + inside.size().cwiseProduct(Vec3(u(rng), u(rng), u(rng))); };
  int hits = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int a = trial % 2;
    if (trial % 50 == 0) {
      Vec3 p = random_point();
      while (exact.place_agent(a, p), exact.overlap(a)) p = random_point();
      fast.place_agent(a, p);
    }
    const Vec3 from = exact.agent_position(a);
    // Mostly game-sized steps, some long ones.
    const double length = u(rng) < 0.8 ? 0.2 * u(rng) : 8.0 * u(rng);
    const Vec3 dir = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    const Vec3 to = inside.clamp(from + length * dir);
    const auto ce = exact.move_agent(a, to);
    const auto cf = fast.move_agent(a, to);
    ASSERT_EQ(ce.has_value(), cf.has_value()) << "trial " << trial;
    ASSERT_EQ(exact.agent_position(a), fast.agent_position(a)) << "trial " << trial;
    if (ce) {
      ++hits;
      EXPECT_EQ(ce->kind, cf->kind);
      EXPECT_EQ(ce->obstacle_id, cf->obstacle_id);
      EXPECT_EQ(ce->fraction, cf->fraction);
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_LT(fast.sweep_count(), exact.sweep_count() * 3 / 4);  // faces and 40 spheres leave little free room
  RecordProperty("sweeps_always", std::to_string(exact.sweep_count()));
  RecordProperty("sweeps_with_early_out", std::to_string(fast.sweep_count()));
}

// A long sequence of random moves (seeded) of one agent in `world`: every contact's identity, fraction and
// point, and every position, folded into a list for comparison.
std::vector<double> random_walk(CollisionWorld& world, std::uint64_t seed, int moves) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box inside = world.arena().bounds();
  const int a = world.add_agent(0.3);
  std::vector<double> out;
  for (int k = 0; k < moves; ++k) {
    if (k % 40 == 0) {
      Vec3 p = inside.lo + inside.size().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
      while (world.place_agent(a, p), world.overlap(a)) p = inside.lo + inside.size().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    }
    const Vec3 dir = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    const Vec3 to = inside.clamp(world.agent_position(a) + (u(rng) < 0.9 ? 0.2 : 6.0) * u(rng) * dir);
    if (const auto c = world.move_agent(a, to)) {
      out.insert(out.end(), {double(c->kind), double(c->obstacle_id), double(c->triangle), c->fraction, c->point.x()});
    }
    const Vec3 p = world.agent_position(a);
    out.insert(out.end(), {p.x(), p.y(), p.z()});
  }
  return out;
}

TEST(WorldCollision, WorldsOverOneArenaAreIndependentAcrossThreads) {
  // Two worlds over one shared arena (spheres, a cylinder and two terrain meshes whose triangles Bullet reads
  // in place) moved concurrently on two threads give exactly what each gives alone on this thread.
  MapSpec spec = load_map(testing::source_dir() / "maps" / "paper.yaml");
  spec.cylinders.push_back({Vec3(17.5, 17.5, 0), 1.5, 12});
  spec.meshes.push_back(testing::mesh_entry("ridge.obj", Vec3(5, 12, 0)));
  spec.meshes.push_back(testing::mesh_entry("wall.obj", Vec3(12, 25, 4), 0.8));
  const auto arena = arena_with(spec);
  constexpr int kMoves = 20000;
  std::vector<double> alone[2];
  for (int t = 0; t < 2; ++t) {
    CollisionWorld w(arena);
    alone[t] = random_walk(w, 100 + t, kMoves);
  }
  std::vector<double> together[2];
  std::latch start(2);
  {
    std::vector<std::jthread> threads;
    for (int t = 0; t < 2; ++t) {
      threads.emplace_back([&, t] {
        CollisionWorld w(arena);
        start.arrive_and_wait();  // both walk at the same time
        together[t] = random_walk(w, 100 + t, kMoves);
      });
    }
  }
  for (int t = 0; t < 2; ++t) {
    ASSERT_GT(alone[t].size(), std::size_t(3 * kMoves));  // some contacts among the positions
    EXPECT_EQ(together[t], alone[t]) << "thread " << t;
  }
  EXPECT_NE(alone[0], alone[1]);
}

TEST(WorldCollision, WorldsOverOneArenaShareItsTerrainHierarchy) {
  // Building a terrain's hierarchy costs about a second per million triangles: once per Arena, not per world.
  MapSpec spec = empty_spec(Vec3(20, 10, 8), 0.2);
  spec.meshes.push_back(testing::mesh_entry("ridge.obj"));
  const auto arena = arena_with(spec);
  const auto shapes = arena->terrain_shapes();
  const long before = shapes.use_count();
  {
    CollisionWorld w1(arena), w2(arena);
    EXPECT_EQ(arena->terrain_shapes(), shapes);
    EXPECT_EQ(shapes.use_count(), before + 2);  // each world holds the Arena's, none built its own
  }
  EXPECT_EQ(shapes.use_count(), before);
}

TEST(WorldCollision, MovingInOneWorldLeavesAnotherAlone) {
  MapSpec spec = empty_spec(Vec3::Constant(10), 0.25);
  spec.spheres.push_back({Vec3(5, 5, 5), 1.0});
  const auto arena = arena_with(spec);
  CollisionWorld w1(arena), w2(arena);
  w1.add_agent(0.5);
  w2.add_agent(0.5);
  w1.place_agent(0, Vec3(1, 5, 5));
  w2.place_agent(0, Vec3(1, 5, 5));
  ASSERT_TRUE(w1.move_agent(0, Vec3(9, 5, 5)).has_value());
  EXPECT_EQ(w2.agent_position(0), Vec3(1, 5, 5));
  EXPECT_EQ(&w1.arena(), &w2.arena());
}

}  // namespace
}  // namespace peg3d::world
