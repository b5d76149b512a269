// peg-bench-world: cost of the world's hot paths on maps/paper.yaml.
//   BM_NearestObstacle/<cm>         one distance-field query at a uniformly random point, resolution <cm> cm
//   BM_NearestObstacleAlongPath/<cm>  one query per step of a random walk (0.11 m steps), as an agent makes them
//   BM_MoveTwoAgents/<early_out>    one game step's collision work: move_agent for two agents (radius 0.25 m,
//                                   0.11 and 0.10 m per step as in the paper), with or without the
//                                   distance-field early-out
//   BM_MoverSensing/<method>/<movers>  one game step of sensing among moving obstacles for two agents near them:
//                                   method 0 exact (static field + each mover's exact distance), 1 octree
//                                   (movers' voxels marked and dynamicEDT3D updated incrementally); counters
//                                   mean_error_m and max_error_m against the exact distance
//   BM_StaticScan/<map>             one 64-ray scan (8 x 8 rays over 120 x 40 degrees about a random heading, 20 m
//                                   range) from a free point of a random walk, against the static scene
//                                   (sense::StaticRayScene): map 0 maps/valley.yaml (terrain), 1 maps/forest.yaml,
//                                   2 maps/quarry.yaml (terrain and its static solids), 3 the paper's arena with
//                                   1000 random spheres and cylinders; items_per_second is rays per second
//   BM_WorldScan/<map>/<range_m>    the same with the movers where they are at the scan's instant (quarry: 520
//                                   bodies and 120 scripted movers), scans 0.1 s apart, each cast at once as the
//                                   game casts it (sense::cast_all), within range_m (10: a lidar's default)
//   BM_SightTest/<points>           one sight test (sense::line_of_sight with `points` sight points) from each point
//                                   of BM_WorldScan/2's walk on maps/quarry.yaml to a sphere of 0.25 m at a random
//                                   free point 3 to 30 m away, the movers where they are at the walk's instant;
//                                   items_per_second is pairs per second; counter share_seen
//   BM_MapInsert/<method>           one 64-ray scan of BM_StaticScan/1 (forest) at 10 m range inserted into an agent's
//                                   map at 0.25 m: method 0 sense::ScanMap::insert, 1 OctoMap's
//                                   OcTree::insertPointCloud (the same scans: the same cells), 2 OctoMap's
//                                   computeRayKeys alone for the same rays (the traversal, no cell updated), 3
//                                   sense::trace_rays for them (the same keys, eight rays at a time in vector
//                                   lanes where the processor has AVX2); the walk's 2000 scans, then the
//                                   walk again into the same map; items_per_second is rays per second; counter
//                                   free_cells_per_ray
//   BM_MapNearest/<cap_m>           the nearest occupied cell of that map (all 2000 scans in) from the walk's points,
//                                   within cap_m
//   BM_CameraImage/<map>/<range_m>/<by_ray>  one 64 x 48 depth image (sense::DepthCamera, 90 deg wide: 3 072
//                                   coherent rays) from each point of the walk of BM_StaticScan/<map>, along its first
//                                   ray, the movers where they are at the image's instant (quarry: 640), as the game
//                                   casts it (sense::cast_image; by_ray 1: ray by ray as the lidar, sense::cast_all);
//                                   items_per_second is images per second, counter s_per_ray (65n: 65 ns)
// Run: build/bin/peg-bench-world [--benchmark_filter=...]

#include <map>
#include <memory>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <octomap/OcTree.h>

#include "cli_common.hpp"
#include "core/random.hpp"
#include "sense/ray_keys.hpp"
#include "sense/scan_map.hpp"
#include "world/arena.hpp"
#include "world/collision/collision_world.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"
#include "world/bodies/mover_timeline.hpp"
#include "world/moving_field.hpp"
#include "sense/depth_camera.hpp"
#include "sense/image_cast.hpp"
#include "sense/line_of_sight.hpp"
#include "sense/static_ray_scene.hpp"
#include "sense/world_rays.hpp"

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

// The paper's arena (no static obstacles, faces not obstacles) with n balls and boxes on random orbits.
std::shared_ptr<const Arena> mover_arena(int n) {
  static std::map<int, std::shared_ptr<const Arena>> built;
  auto& a = built[n];
  if (a) return a;
  MapSpec m;
  m.name = "movers";
  m.bounds = {Vec3::Zero(), Vec3(35, 35, 20)};
  m.resolution = 0.2;
  m.max_distance = 5.0;
  m.floor_is_obstacle = m.ceiling_is_obstacle = m.walls_is_obstacle = false;
  Rng rng{static_cast<std::uint64_t>(n)};
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    MoverSpec mv;
    mv.shape = i % 2 == 0 ? Shape{Shape::Kind::kSphere, 0.5 + 0.5 * u(rng), 1.0, Vec3::Ones()}
                          : Shape{Shape::Kind::kBox, 1.0, 1.0, Vec3(0.8 + u(rng), 0.8 + u(rng), 0.8 + u(rng))};
    mv.motion = MoverSpec::Motion::kOrbit;
    mv.orbit.radius = 2.0 + 4.0 * u(rng);
    mv.orbit.center = Vec3(8.5 + 18.0 * u(rng), 8.5 + 18.0 * u(rng), 3.0 + 14.0 * u(rng));
    mv.orbit.axis = Vec3(0.3 * (u(rng) - 0.5), 0.3 * (u(rng) - 0.5), 1.0);
    mv.orbit.period = 10.0 + 20.0 * u(rng);
    mv.orbit.phase = 6.28 * u(rng);
    mv.orbit.center.z() = std::clamp(mv.orbit.center.z(), 2.5 + mv.orbit.radius * 0.15, 17.5 - mv.orbit.radius * 0.15);
    m.movers.push_back(mv);
  }
  a = Arena::build(m);
  return a;
}

// Distance from p to the nearest mover at time t: the exact answer.
double exact_distance(const MoverTimeline& t, const Vec3& p, double time) {
  double best = 1e9;
  for (int m = 0; m < t.count(); ++m) best = std::min(best, nearest_on_shape(t.mover(m).shape, t.pose(m, time), p).distance);
  return best;
}

void BM_MoverSensing(benchmark::State& state) {
  const bool octree = state.range(0) == 1;
  const int n = static_cast<int>(state.range(1));
  const auto arena = mover_arena(n);
  const auto timeline = arena->movers_until(200.0);
  std::unique_ptr<MovingOccupancyField> field;
  if (octree) field = std::make_unique<MovingOccupancyField>(*arena);
  Rng rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), gap(0.3, 3.0);
  double t = 0.0, error_sum = 0.0, error_max = 0.0;
  long queries = 0;
  for (auto _ : state) {
    t += 0.1;
    if (t > 199.0) t = 0.1;
    // Two query points 0.3-3 m from the surface of random movers (the agents near them).
    state.PauseTiming();
    Vec3 q[2];
    for (auto& p : q) {
      const int m = static_cast<int>((u(rng) + 1.0) * 0.5 * n) % n;
      const Pose at = timeline->pose(m, t);
      const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
      p = arena->bounds().shrunk(0.3).clamp(at.position + (timeline->mover(m).shape.bounding_radius() + gap(rng)) * dir);
    }
    state.ResumeTiming();
    double sensed[2];
    if (octree) {
      field->set_time(*timeline, t);
      for (int i = 0; i < 2; ++i) sensed[i] = field->nearest(q[i]).distance;
    } else {
      for (int i = 0; i < 2; ++i) {
        const NearestObstacle s = arena->nearest_shape(q[i]);
        const MoverPoint mp = timeline->nearest(q[i], t, s.distance);
        sensed[i] = mp.mover >= 0 ? mp.distance : s.distance;
      }
    }
    state.PauseTiming();
    for (int i = 0; i < 2; ++i) {
      const double exact = std::min(exact_distance(*timeline, q[i], t), arena->max_distance());
      const double e = std::abs(sensed[i] - exact);
      error_sum += e;
      error_max = std::max(error_max, e);
      ++queries;
    }
    state.ResumeTiming();
  }
  state.counters["mean_error_m"] = queries ? error_sum / queries : 0.0;
  state.counters["max_error_m"] = error_max;
  state.SetItemsProcessed(state.iterations());
}
// The octree's incremental EDT is slow: fewer steps measured for it (every step is one game step, 0.1 s apart).
BENCHMARK(BM_MoverSensing)->ArgsProduct({{0}, {1, 10, 100}})->Unit(benchmark::kMicrosecond)->Iterations(500);
BENCHMARK(BM_MoverSensing)->ArgsProduct({{1}, {1, 10}})->Unit(benchmark::kMicrosecond)->Iterations(20);
BENCHMARK(BM_MoverSensing)->Args({1, 100})->Unit(benchmark::kMicrosecond)->Iterations(3);

std::shared_ptr<const Arena> scan_arena(int which) {
  static std::map<int, std::shared_ptr<const Arena>> built;
  auto& a = built[which];
  if (a) return a;
  if (which < 3) {
    const char* maps[] = {"maps/valley.yaml", "maps/forest.yaml", "maps/quarry.yaml"};
    return a = Arena::build(load_map(peg3d::cli::data_dir() / maps[which]));
  }
  MapSpec m = load_map(peg3d::cli::data_dir() / "maps/paper.yaml");
  Rng rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3 lo = m.bounds.lo, size = m.bounds.size();
  for (int i = 0; i < 500; ++i) {
    m.spheres.push_back({lo + size.cwiseProduct(Vec3(u(rng), u(rng), u(rng))), 0.3 + 0.7 * u(rng)});
    const Vec3 base = lo + size.cwiseProduct(Vec3(u(rng), u(rng), 0.0));
    m.cylinders.push_back({base, 0.2 + 0.5 * u(rng), 1.0 + 8.0 * u(rng)});
  }
  m.scenarios.clear();
  return a = Arena::build(m);
}

// 2 000 scans of 64 rays along a random walk of 0.1 m steps through free space (as an agent scans at 10 Hz), each
// about a random heading: 8 x 8 rays over 120 x 40 degrees. The walk starts at the free point nearest the arena's
// centre on a grid of 0.5 m (forest's old oak stands at the centre).
constexpr int kScans = 2000, kRays = 64;
std::vector<Ray> walk_scans(const Arena& arena) {
  const Box inner = arena.bounds().shrunk(0.5);
  const Vec3 centre = arena.bounds().lo + 0.5 * arena.bounds().size();
  Vec3 p = inner.clamp(centre);
  for (double r = 0.0; arena.nearest_obstacle(p).distance <= 0.5 && r < 20.0; r += 0.5) {
    for (int k = 0; k < 16 && arena.nearest_obstacle(p).distance <= 0.5; ++k) {
      p = inner.clamp(centre + r * Vec3(std::cos(k * 3.14159 / 8), std::sin(k * 3.14159 / 8), 0.0));
    }
  }
  Rng rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Ray> rays(std::size_t(kScans) * kRays);
  for (int s = 0; s < kScans; ++s) {
    for (int tries = 0; tries < 50; ++tries) {
      const Vec3 next = inner.clamp(p + 0.1 * Vec3(u(rng), u(rng), 0.3 * u(rng)).normalized());
      if (arena.nearest_obstacle(next).distance > 0.3) {
        p = next;
        break;
      }
    }
    const double heading = 3.14159 * u(rng);
    for (int i = 0; i < 8; ++i) {
      for (int j = 0; j < 8; ++j) {
        const double az = heading + (i - 3.5) * (120.0 / 7.0) * 3.14159 / 180.0;
        const double el = (j - 3.5) * (40.0 / 7.0) * 3.14159 / 180.0;
        rays[std::size_t(s * kRays + 8 * i + j)] = {p, Vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el))};
      }
    }
  }
  return rays;
}

// Scans of BM_StaticScan/<map>; with `movers`, against the movers too, scan s at time 0.1 s (each step's).
void scan_benchmark(benchmark::State& state, bool movers) {
  const auto arena = scan_arena(static_cast<int>(state.range(0)));
  const sense::StaticRayScene scene(*arena);
  const auto timeline = movers ? arena->movers_until(200.0) : nullptr;
  // The timeline simulates its blocks on first use: a query at the last instant the scans reach simulates them
  // all before timing.
  if (timeline) timeline->nearest(arena->bounds().lo, 199.9, 1.0);
  const double range = movers ? double(state.range(1)) : 20.0;  // m
  const std::vector<Ray> rays = walk_scans(*arena);
  std::vector<sense::RayHit> hits(kRays);
  long scans = 0, met = 0;
  for (auto _ : state) {
    const std::size_t s = std::size_t(scans % kScans);
    if (timeline) {
      const double t = 0.1 * static_cast<double>(s);
      sense::WorldAtInstant w;  // the scan at once, as the game casts it
      w.scene = &scene, w.movers = timeline.get(), w.time = t;
      sense::cast_all(w, std::span<const Ray>(rays).subspan(s * kRays, kRays), range, -1, hits);
    } else {
      scene.cast(std::span<const Ray>(rays).subspan(s * kRays, kRays), range, hits);
    }
    benchmark::DoNotOptimize(hits.data());
    if (scans < kScans) {
      for (const auto& h : hits) met += h.target != sense::RayTarget::kNone;
    }
    ++scans;
  }
  state.SetItemsProcessed(scans * kRays);  // rays per second; ns per ray = 1e9 / items_per_second
  state.counters["share_hit"] = double(met) / double(std::min<long>(scans, kScans) * kRays);
}
void BM_SightTest(benchmark::State& state) {
  const int points = static_cast<int>(state.range(0));
  const auto arena = scan_arena(2);
  const sense::StaticRayScene scene(*arena);
  const auto timeline = arena->movers_until(200.0);
  timeline->nearest(arena->bounds().lo, 199.9, 1.0);  // every block simulated before timing
  const std::vector<Ray> rays = walk_scans(*arena);
  Rng rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box inner = arena->bounds().shrunk(0.5);
  std::vector<Vec3> targets(kScans);
  for (int s = 0; s < kScans; ++s) {
    const Vec3& eye = rays[std::size_t(s) * kRays].origin;
    Vec3 t;
    do t = inner.lo + inner.size().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    while (arena->nearest_obstacle(t).distance < 0.3 || (t - eye).norm() < 3.0 || (t - eye).norm() > 30.0);
    targets[std::size_t(s)] = t;
  }
  long pairs = 0, seen = 0;
  for (auto _ : state) {
    const std::size_t s = std::size_t(pairs % kScans);
    sense::WorldAtInstant w;
    w.scene = &scene, w.movers = timeline.get(), w.time = 0.1 * static_cast<double>(s);
    const bool in_sight = sense::line_of_sight(w, rays[s * kRays].origin, targets[s], 0.25, points);
    benchmark::DoNotOptimize(in_sight);
    if (pairs < kScans) seen += in_sight;
    ++pairs;
  }
  state.SetItemsProcessed(pairs);
  state.counters["share_seen"] = double(seen) / double(std::min<long>(pairs, kScans));
}
BENCHMARK(BM_SightTest)->Arg(1)->Arg(5)->Arg(9)->Unit(benchmark::kMicrosecond);

// BM_MapInsert/<method>: the scans' endpoints (an echo's, or one beyond the range) along the forest walk.
void BM_MapInsert(benchmark::State& state) {
  const bool octomap_tree = state.range(0) == 1, keys_only = state.range(0) == 2, traced = state.range(0) == 3;
  const auto arena = scan_arena(1);
  const sense::StaticRayScene scene(*arena);
  constexpr double kRange = 10.0;
  const std::vector<Ray> rays = walk_scans(*arena);
  std::vector<sense::RayHit> hits(kRays);
  std::vector<Vec3> origins(kScans), points(std::size_t(kScans) * kRays);
  for (int s = 0; s < kScans; ++s) {
    const auto scan = std::span<const Ray>(rays).subspan(std::size_t(s) * kRays, kRays);
    scene.cast(scan, kRange, hits);
    origins[std::size_t(s)] = scan[0].origin;
    for (int k = 0; k < kRays; ++k) {
      const sense::RayHit& h = hits[std::size_t(k)];
      points[std::size_t(s * kRays + k)] =
          scan[std::size_t(k)].origin + (h.target != sense::RayTarget::kNone ? h.distance : kRange + 1.0) * scan[std::size_t(k)].direction;
    }
  }
  sense::ScanMapConfig config;
  sense::ScanMap map(config, arena->bounds().lo, arena->bounds().hi);
  octomap::OcTree tree(config.resolution);
  std::vector<octomap::Pointcloud> clouds(kScans);
  for (int s = 0; s < kScans; ++s) {
    for (int k = 0; k < kRays; ++k) {
      const Vec3& q = points[std::size_t(s * kRays + k)];
      clouds[std::size_t(s)].push_back(float(q.x()), float(q.y()), float(q.z()));
    }
  }
  long scans = 0;
  // The end of a ray as insertPointCloud traces it: its endpoint, or the point at the range along it.
  const auto traced_end = [&](const octomap::point3d& origin, const octomap::point3d& q) {
    return (q - origin).norm() <= kRange ? q : origin + (q - origin).normalized() * float(kRange);
  };
  octomap::KeyRay ray_keys;
  std::vector<octomap::point3d> ends;
  std::vector<std::uint64_t> packed;
  std::vector<sense::RayKeySpan> spans;
  for (auto _ : state) {
    const auto s = std::size_t(scans % kScans);
    const Vec3& o = origins[s];
    if (traced) {
      const octomap::point3d origin(float(o.x()), float(o.y()), float(o.z()));
      ends.clear();
      for (const octomap::point3d& q : clouds[s]) {
        ends.push_back(traced_end(origin, q));
      }
      benchmark::DoNotOptimize(sense::trace_rays(tree, origin, ends, packed, spans));
    } else if (keys_only) {
      const octomap::point3d origin(float(o.x()), float(o.y()), float(o.z()));
      for (const octomap::point3d& q : clouds[s]) {
        tree.computeRayKeys(origin, traced_end(origin, q), ray_keys);
        benchmark::DoNotOptimize(ray_keys.size());
      }
    } else if (octomap_tree) {
      tree.insertPointCloud(clouds[s], octomap::point3d(float(o.x()), float(o.y()), float(o.z())), kRange);
    } else {
      map.insert(o, std::span<const Vec3>(points).subspan(s * kRays, kRays), kRange);
    }
    ++scans;
  }
  state.SetItemsProcessed(scans * kRays);
  // Free cells a ray crosses, from one pass of OctoMap's key arithmetic over the first scans.
  octomap::KeyRay keys;
  long free_cells = 0;
  for (int s = 0; s < 100; ++s) {
    const Vec3& o = origins[std::size_t(s)];
    const octomap::point3d origin(float(o.x()), float(o.y()), float(o.z()));
    for (const octomap::point3d& q : clouds[std::size_t(s)]) {
      if (tree.computeRayKeys(origin, traced_end(origin, q), keys)) free_cells += static_cast<long>(keys.size());
    }
  }
  state.counters["free_cells_per_ray"] = double(free_cells) / (100.0 * kRays);
}
BENCHMARK(BM_MapInsert)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

// BM_MapNearest/<cap_m>: the nearest occupied cell of the map BM_MapInsert/0 builds from the walk's 2000 scans, from
// each scan's origin in turn, within cap_m.
void BM_MapNearest(benchmark::State& state) {
  const double cap = double(state.range(0));
  const auto arena = scan_arena(1);
  const sense::StaticRayScene scene(*arena);
  constexpr double kRange = 10.0;
  const std::vector<Ray> rays = walk_scans(*arena);
  std::vector<sense::RayHit> hits(kRays);
  std::vector<Vec3> points(kRays);
  sense::ScanMap map(sense::ScanMapConfig{}, arena->bounds().lo, arena->bounds().hi);
  for (int s = 0; s < kScans; ++s) {
    const auto scan = std::span<const Ray>(rays).subspan(std::size_t(s) * kRays, kRays);
    scene.cast(scan, kRange, hits);
    for (int k = 0; k < kRays; ++k) {
      const sense::RayHit& h = hits[std::size_t(k)];
      points[std::size_t(k)] = scan[std::size_t(k)].origin + (h.target != sense::RayTarget::kNone ? h.distance : kRange + 1.0) * scan[std::size_t(k)].direction;
    }
    map.insert(scan[0].origin, points, kRange);
  }
  long queries = 0, found = 0;
  for (auto _ : state) {
    const sense::OccupiedPoint n = map.nearest_occupied(rays[std::size_t(queries % kScans) * kRays].origin, cap);
    benchmark::DoNotOptimize(n);
    found += n.found;
    ++queries;
  }
  state.counters["share_found"] = double(found) / double(queries);
  state.counters["occupied_cells"] = double(map.occupied_cells());
}
BENCHMARK(BM_MapNearest)->Arg(2)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);

// BM_CameraImage/<map>/<range_m>/<by_ray>: a 64 x 48 image from each scan origin of the walk, the scan's heading, at
// the scan's instant (0.1 s apart).
void BM_CameraImage(benchmark::State& state) {
  const auto arena = scan_arena(static_cast<int>(state.range(0)));
  const sense::StaticRayScene scene(*arena);
  const auto timeline = arena->movers_until(200.0);
  if (timeline) timeline->nearest(arena->bounds().lo, 199.9, 1.0);  // every block simulated before timing
  sense::DepthCameraConfig config;
  config.width = 64, config.height = 48, config.range = double(state.range(1));
  const sense::DepthCamera camera(config);
  const std::vector<Ray> walk = walk_scans(*arena);
  std::vector<Ray> rays(std::size_t(camera.pixels()));
  std::vector<sense::RayHit> hits(rays.size());
  sense::ImageCastScratch scratch;
  long images = 0, met = 0;
  for (auto _ : state) {
    const std::size_t s = std::size_t(images % kScans);
    const Ray& look = walk[s * kRays];  // the scan's first ray: its origin, and a heading near the scan's
    const Heading heading = heading_of(look.direction);
    camera.rays_at(look.origin, heading, rays);
    const sense::Pinhole pinhole = camera.pinhole_at(heading);
    sense::WorldAtInstant w;
    w.scene = &scene, w.movers = timeline.get(), w.time = 0.1 * static_cast<double>(s);
    if (state.range(2) != 0) {
      sense::cast_all(w, rays, config.range, -1, hits);
    } else {
      sense::cast_image(w, rays, config.width, &pinhole, config.range, -1, hits, scratch);
    }
    benchmark::DoNotOptimize(hits.data());
    if (images < kScans) {
      for (const auto& h : hits) met += h.target != sense::RayTarget::kNone;
    }
    ++images;
  }
  state.SetItemsProcessed(images);
  // Seconds a ray (printed with an SI prefix: 65n is 65 ns).
  state.counters["s_per_ray"] = benchmark::Counter(double(images) * double(rays.size()),
                                                   benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["share_hit"] = double(met) / double(std::min<long>(images, kScans) * long(rays.size()));
}
BENCHMARK(BM_CameraImage)->ArgsProduct({{1, 2}, {10, 20}, {0, 1}})->Unit(benchmark::kMicrosecond);

void BM_StaticScan(benchmark::State& state) { scan_benchmark(state, false); }
void BM_WorldScan(benchmark::State& state) { scan_benchmark(state, true); }
BENCHMARK(BM_StaticScan)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WorldScan)->Args({2, 10})->Args({2, 20})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
