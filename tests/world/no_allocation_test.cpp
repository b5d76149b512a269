// The hot paths allocate nothing: nearest_obstacle, and move_agent including Bullet's sweep. This file
// replaces the global operator new of the test program with a counting one, and counts Bullet's allocations
// through its allocator hook.

#include <atomic>
#include <cstdlib>
#include <new>
#include <random>

#include <LinearMath/btAlignedAllocator.h>
#include <gtest/gtest.h>

#include "support/counting_new.hpp"
#include "world/collision/collision_world.hpp"
#include "world/map/map_loader.hpp"
#include "world_test_support.hpp"

namespace {
using peg3d::testing::g_allocations;

void* counting_bullet_alloc(std::size_t n) {
  ++g_allocations;
  return std::malloc(n);
}
void bullet_free(void* p) { std::free(p); }
}  // namespace

namespace peg3d::world {
namespace {

TEST(WorldNoAllocation, NearestObstacleAndMoveAgent) {
  MapSpec spec = load_map(testing::source_dir() / "maps" / "paper.yaml");
  spec.meshes.push_back(testing::mesh_entry("ridge.obj", Vec3(5, 12, 0)));
  spec.cylinders.push_back({Vec3(17.5, 17.5, 0), 1.5, 12});
  const auto arena = testing::build(spec);
  CollisionWorld fast(arena), always(arena, CollisionOptions{false});
  for (CollisionWorld* w : {&fast, &always}) {
    w->add_agent(0.3);
    w->add_agent(0.3);
  }
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> targets(4096, Vec3::Zero());
  for (auto& t : targets) t = arena->bounds().lo + arena->bounds().size().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
  auto run = [&](int moves) {
    double sum = 0.0;
    for (int i = 0; i < moves; ++i) {
      const Vec3& t = targets[std::size_t(i) & 4095];
      sum += arena->nearest_obstacle(t).distance;
      for (CollisionWorld* w : {&fast, &always}) {
        const int a = i & 1;
        // Long hops towards random targets hit obstacles often; short ones exercise the early-out.
        const Vec3 from = w->agent_position(a);
        const Vec3 to = (i % 3 == 0) ? t : from + 0.1 * (t - from).normalized();
        w->move_agent(a, to);
        if (i % 7 == 0) w->place_agent(a, targets[std::size_t(i * 31) & 4095]);
      }
    }
    return sum;
  };
  run(2000);  // warm up: Bullet sizes its internal stacks on first use
  btAlignedAllocSetCustom(counting_bullet_alloc, bullet_free);
  const long before = g_allocations.load();
  const double sum = run(20000);
  const long allocations = g_allocations.load() - before;
  btAlignedAllocSetCustom(std::malloc, bullet_free);
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(sum, 0.0);
  EXPECT_GT(always.sweep_count(), 10000);
}

}  // namespace
}  // namespace peg3d::world
