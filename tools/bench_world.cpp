// peg-bench-world: cost of the world's hot paths on maps/paper.yaml.
//   BM_NearestObstacle/<cm>         one distance-field query at a uniformly random point, resolution <cm> cm
//   BM_NearestObstacleAlongPath/<cm>  one query per step of a random walk (0.11 m steps), as an agent makes them
//   BM_MoveTwoAgents/<early_out>    one game step's collision work: move_agent for two agents (radius 0.25 m,
//                                   0.11 and 0.10 m per step as in the paper), with or without the
//                                   distance-field early-out
// Run: build/bin/peg-bench-world [--benchmark_filter=...]

#include <map>
#include <memory>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "cli_common.hpp"
#include "core/random.hpp"
#include "world/arena.hpp"
#include "world/collision_world.hpp"
#include "world/map_spec.hpp"

namespace {

using namespace peg3d;
using namespace peg3d::world;

std::shared_ptr<const Arena> paper_arena(double resolution) {
  static std::map<double, std::shared_ptr<const Arena>> built;
  auto& a = built[resolution];
  if (!a) {
    BuildOptions options;
    options.resolution_override = resolution;
    a = Arena::build(load_map(peg3d::cli::data_dir() / "maps/paper.yaml"), options);
  }
  return a;
}

std::vector<Vec3> random_points(const Box& box, std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> pts(n);
  for (auto& p : pts) p = box.lo + box.size().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
  return pts;
}

void BM_NearestObstacle(benchmark::State& state) {
  const auto arena = paper_arena(state.range(0) / 100.0);
  const auto pts = random_points(arena->bounds(), 1 << 16, 1);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(arena->nearest_obstacle(pts[i]));
    i = (i + 1) & (pts.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NearestObstacle)->Arg(10)->Arg(20)->Arg(25);

// Queries along a random walk of 0.11 m steps, as an agent makes them: neighbouring cells, warm caches.
void BM_NearestObstacleAlongPath(benchmark::State& state) {
  const auto arena = paper_arena(state.range(0) / 100.0);
  const Box inside = arena->bounds().shrunk(0.25);
  Rng rng(3);
  std::normal_distribution<double> n;
  std::vector<Vec3> path(1 << 16);
  Vec3 p = arena->map().scenarios.front().pursuers.front().position, dir = Vec3::UnitX();
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (i % 20 == 0) dir = Vec3(n(rng), n(rng), n(rng)).normalized();
    p = inside.clamp(p + 0.11 * dir);
    path[i] = p;
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(arena->nearest_obstacle(path[i]));
    i = (i + 1) & (path.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NearestObstacleAlongPath)->Arg(10)->Arg(20)->Arg(25);

void BM_MoveTwoAgents(benchmark::State& state) {
  const auto arena = paper_arena(0.2);
  CollisionWorld world(arena, CollisionOptions{state.range(0) != 0});
  const double radius = 0.25;
  const double steps[2] = {0.11, 0.10};
  const Box inside = arena->bounds().shrunk(radius);
  const Scenario& s = arena->map().scenarios.front();
  const int agent[2] = {world.add_agent(radius), world.add_agent(radius)};
  world.place_agent(agent[0], s.pursuers.front().position);
  world.place_agent(agent[1], s.evaders.front().position);
  // Random walk: each agent keeps a direction for 20 steps, then takes the next from a table.
  Rng rng(7);
  std::normal_distribution<double> n;
  std::vector<Vec3> dirs(4096);
  for (auto& d : dirs) d = Vec3(n(rng), n(rng), n(rng)).normalized();
  std::size_t k = 0, step = 0;
  Vec3 dir[2] = {dirs[0], dirs[1]};
  long long contacts = 0;
  for (auto _ : state) {
    if (++step % 20 == 0) dir[0] = dirs[k++ & 4095], dir[1] = dirs[k++ & 4095];
    for (int a = 0; a < 2; ++a) {
      const Vec3 to = inside.clamp(world.agent_position(agent[a]) + steps[a] * dir[a]);
      if (world.move_agent(agent[a], to)) {
        ++contacts;
        dir[a] = dirs[k++ & 4095];
      }
    }
  }
  state.SetItemsProcessed(2 * state.iterations());
  state.counters["contacts"] = benchmark::Counter(double(contacts));
  state.counters["sweeps/step"] = double(world.sweep_count()) / double(state.iterations());
}
BENCHMARK(BM_MoveTwoAgents)->Arg(1)->Arg(0);

}  // namespace

BENCHMARK_MAIN();
