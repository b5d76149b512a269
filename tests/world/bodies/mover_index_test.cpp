// The movers' timeline as a store and an index (world/bodies/mover_timeline.hpp): the indexed queries give the answers
// of a visit of every mover, to the bit, on a crowded map of scripted movers (slow and fast, every shape) and
// dynamic bodies; bodies at rest are stored once; keyframes thinned by physics.keyframe_hz are the simulated
// poses; the worst case is checked against the budget before anything is simulated; blocks are simulated only
// when a query reaches them.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <thread>

#include "world/arena.hpp"
#include "world/bodies/mover_timeline.hpp"
#include "world/map/movers.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

MoverSpec orbit(const Vec3& center, double radius, double period, double phase, const Shape& shape) {
  MoverSpec m;
  m.shape = shape;
  m.motion = MoverSpec::Motion::kOrbit;
  m.orbit = {center, radius, period, Vec3::UnitZ(), phase};
  return m;
}

MoverSpec path(const Vec3& a, const Vec3& b, double speed, const Shape& shape) {
  MoverSpec m;
  m.shape = shape;
  m.motion = MoverSpec::Motion::kPath;
  m.path = {{a, b}, speed, false};
  return m;
}

MoverSpec body(const Vec3& at, const Shape& shape) {
  MoverSpec m;
  m.shape = shape;
  m.motion = MoverSpec::Motion::kDynamic;
  m.start = at;
  m.dynamic.mass = 5.0;
  m.dynamic.restitution = 0.3;
  return m;
}

const Shape kBall{Shape::Kind::kSphere, 0.4, 1.0, Vec3::Ones()};
const Shape kPost{Shape::Kind::kCylinder, 0.3, 1.2, Vec3::Ones()};
const Shape kCrate{Shape::Kind::kBox, 1.0, 1.0, Vec3(0.8, 0.5, 0.6)};

// 300 movers in a 30 m box: orbits and paths of every shape (with `fast`, some at 25 m/s, several arena widths a
// second, and orbits up to 15 m/s; else at most 4 m/s), and dynamic bodies dropped onto the floor, that bounce
// and come to rest.
MapSpec crowded(int keyframe_hz = 0, bool fast = true) {
  MapSpec spec = testing::empty_spec(Vec3(30, 30, 15), 0.5);
  spec.physics.keyframe_hz = keyframe_hz;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Shape shapes[] = {kBall, kPost, kCrate};
  for (int k = 0; k < 100; ++k) {
    spec.movers.push_back(orbit(Vec3(15, 15, 2 + 11 * u(rng)), 2 + 10 * u(rng), (fast ? 5 : 20) + 20 * u(rng), 6 * u(rng), shapes[k % 3]));
  }
  for (int k = 0; k < 100; ++k) {
    const double y = 2 + 26 * u(rng), z = 2 + 11 * u(rng);
    spec.movers.push_back(path(Vec3(2, y, z), Vec3(28, y, z), k % 10 == 0 && fast ? 25.0 : 0.5 + 3 * u(rng), shapes[k % 3]));
  }
  for (int k = 0; k < 100; ++k) {
    spec.movers.push_back(body(Vec3(1.5 + (k % 10) * 2.9, 1.5 + (k / 10) * 2.9, 1 + 5 * u(rng)), shapes[k % 2 == 0 ? 0 : 2]));
  }
  return spec;
}

bool same(const MoverPoint& a, const MoverPoint& b) {
  return a.mover == b.mover && std::memcmp(&a.distance, &b.distance, sizeof(double)) == 0 && a.point == b.point;
}

bool same(const std::optional<Contact>& a, const std::optional<Contact>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->obstacle_id == b->obstacle_id && std::memcmp(&a->fraction, &b->fraction, sizeof(double)) == 0 && a->point == b->point &&
         a->normal == b->normal && a->penetration == b->penetration;
}

TEST(WorldMoverIndex, IndexedQueriesGiveTheAnswersOfAVisitOfEveryMover) {
  const auto arena = testing::build(crowded());
  const auto t = arena->movers_until(12.0);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int near = 0, contacts = 0;
  for (int q = 0; q < 4000; ++q) {
    const double time = 11.9 * u(rng), dt = q % 4 == 0 ? 0.05 : 0.1;
    const Vec3 p(30 * u(rng), 30 * u(rng), 15 * u(rng));
    const double cap = q % 2 == 0 ? 5.0 : 1.5;
    const MoverPoint a = t->nearest(p, time, cap), b = t->nearest_scan(p, time, cap);
    ASSERT_TRUE(same(a, b)) << "query " << q << ": mover " << a.mover << " at " << a.distance << " against "
                            << b.mover << " at " << b.distance;
    // A hint (the answer, any mover, none, none that exists) changes where the search starts, not its answer.
    for (const int hint : {b.mover, int(q % t->count()), -1, t->count()}) {
      ASSERT_TRUE(same(t->nearest(p, time, cap, hint), b)) << "query " << q << " with hint " << hint;
    }
    near += a.mover >= 0;
    // Agents' moves from a standstill to 3 m, some from inside a mover's path.
    const Vec3 to = p + Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * (q % 5 == 0 ? 0.0 : 6.0);
    const auto c = t->first_contact(p, to, 0.25, time, dt), d = t->first_contact_scan(p, to, 0.25, time, dt);
    ASSERT_TRUE(same(c, d)) << "query " << q;
    contacts += c.has_value();
  }
  std::printf("%d of 4000 points with a mover within the cap, %d contacts\n", near, contacts);
  EXPECT_GT(near, 1000);
  EXPECT_GT(contacts, 300);
}

TEST(WorldMoverIndex, ARayMeetsTheMoverAVisitOfEveryMoverFindsAtTheSameDistance) {
  // Rays from anywhere in any direction at any time of the crowded map (scripted movers of every shape, slow and
  // fast, and falling bodies): the indexed query answers the scan's mover at its distance, to the bit.
  const auto arena = testing::build(crowded());
  const auto t = arena->movers_until(12.0);
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  int met = 0;
  for (int q = 0; q < 4000; ++q) {
    const double time = 11.9 * u(rng), range = q % 3 == 0 ? 3.0 : 40.0;
    const Ray ray{{30 * u(rng), 30 * u(rng), 15 * u(rng)}, Vec3(n(rng), n(rng), n(rng)).normalized()};
    const MoverHit a = t->first_along(ray, time, range), b = t->first_along_scan(ray, time, range);
    ASSERT_EQ(a.mover, b.mover) << "query " << q;
    ASSERT_EQ(std::memcmp(&a.distance, &b.distance, sizeof(double)), 0) << "query " << q << ": " << a.distance << " " << b.distance;
    met += a.mover >= 0;
  }
  std::printf("%d of 4000 rays met a mover\n", met);
  EXPECT_GT(met, 300);
  EXPECT_LT(met, 3700);
}

TEST(WorldMoverIndex, AFanOfRaysMeetsWhatEachOfItsRaysMeetsAlone) {
  // Scans of 1 to 64 rays from one point at any time of the crowded map, inside the timeline and past it, with
  // ranges of 0 to 40 m that differ from ray to ray: each ray's answer is the scan's, to the bit.
  const auto arena = testing::build(crowded());
  const auto t = arena->movers_until(12.0);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  int met = 0, rays_cast = 0;
  for (int q = 0; q < 600; ++q) {
    const double time = q % 50 == 7 ? 12.5 : 11.9 * u(rng);
    const Vec3 origin(30 * u(rng), 30 * u(rng), 15 * u(rng));
    const int rays = q % 3 == 0 ? BoxIndex::kFanRays : 1 + int(rng() % BoxIndex::kFanRays);
    std::vector<Vec3> directions(static_cast<std::size_t>(rays));
    std::vector<MoverHit> fan(static_cast<std::size_t>(rays));
    for (int k = 0; k < rays; ++k) {
      directions[std::size_t(k)] = Vec3(n(rng), n(rng), n(rng)).normalized();
      fan[std::size_t(k)] = {-1, k % 17 == 4 ? 0.0 : 40.0 * u(rng)};
    }
    const std::vector<MoverHit> ranges = fan;
    t->first_along_fan(origin, directions, time, fan);
    for (int k = 0; k < rays; ++k) {
      const MoverHit alone = t->first_along_scan({origin, directions[std::size_t(k)]}, time, ranges[std::size_t(k)].distance);
      const MoverHit& a = fan[std::size_t(k)];
      ASSERT_EQ(a.mover, alone.mover) << "query " << q << " ray " << k;
      ASSERT_EQ(std::memcmp(&a.distance, &alone.distance, sizeof(double)), 0) << "query " << q << " ray " << k;
      met += a.mover >= 0;
    }
    rays_cast += rays;
  }
  std::printf("%d of %d rays met a mover\n", met, rays_cast);
  EXPECT_GT(met, rays_cast / 20);
  EXPECT_LT(met, rays_cast * 19 / 20);
}

TEST(WorldMoverIndex, NoPointOfAnyMoverTravelsFartherThanTheBound) {
  // Points of every mover (its centre, a box's corners, a point off the centre) between two instants of a game
  // step: all movers, the bodies alone (bouncing, tumbling and rolling), the scripted movers alone, whose
  // fastest one's straight run reaches the bound (the bound is not vacuous).
  enum Which { kAll, kBodies, kScripted };
  for (const Which which : {kAll, kBodies, kScripted}) {
    MapSpec spec = crowded();
    if (which == kScripted) spec.movers.resize(200);  // the orbits and paths
    if (which == kBodies) spec.movers.erase(spec.movers.begin(), spec.movers.begin() + 200);
    const auto t = testing::build(spec)->movers_until(12.0);
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double nearest_to_bound = 0.0;
    for (int q = 0; q < 2000; ++q) {
      const double t0 = 11.8 * u(rng), t1 = t0 + 0.1 * u(rng);
      const double bound = t->max_travel(t0, t1);
      for (int m = 0; m < t->count(); ++m) {
        const Pose a = t->pose(m, t0), b = t->pose(m, t1);
        const Vec3 half = t->mover(m).shape.kind == Shape::Kind::kBox ? Vec3(0.5 * t->mover(m).shape.size) : Vec3::Zero();
        for (const Vec3& local : {Vec3(Vec3::Zero()), half, Vec3(-half), Vec3(0.3, -0.2, 0.25)}) {
          const double moved = (b.position + b.orientation * local - a.position - a.orientation * local).norm();
          ASSERT_LE(moved, bound + 1e-12) << "mover " << m << " from " << t0 << " to " << t1;  // to rounding
          if (bound > 0.0) nearest_to_bound = std::max(nearest_to_bound, moved / bound);
        }
      }
    }
    if (which == kScripted) {
      EXPECT_GT(nearest_to_bound, 0.999);
    }
  }
}

TEST(WorldMoverIndex, AClearanceThatRulesOutAContactRulesItOut) {
  // Agents' steps (0 to 0.3 m in 0.1 s) from random points, each with the clearance its view would give (the
  // nearest mover's distance, or the cap no mover came within): whenever clear_of_contact says no mover can
  // touch, a visit of every mover finds no contact. Slow movers make it say so often; fast ones rarely.
  for (const bool fast : {false, true}) {
    const auto t = testing::build(crowded(0, fast))->movers_until(12.0);
    std::mt19937_64 rng(fast ? 3 : 8);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int clear = 0, contacts = 0;
    for (int q = 0; q < 6000; ++q) {
      const double time = 11.8 * u(rng), cap = q % 2 == 0 ? 5.0 : 2.0;
      const Vec3 p(30 * u(rng), 30 * u(rng), 15 * u(rng));
      const Vec3 to = p + Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized() * 0.3 * u(rng);
      const MoverPoint seen = t->nearest_scan(p, time, cap);
      const double clearance = seen.mover >= 0 ? seen.distance : cap;
      const auto contact = t->first_contact_scan(p, to, 0.25, time, 0.1);
      contacts += contact.has_value();
      if (!t->clear_of_contact(clearance, p, to, 0.25, time, 0.1)) continue;
      ++clear;
      ASSERT_FALSE(contact.has_value()) << "query " << q << ": mover " << contact->obstacle_id << " touches";
    }
    std::printf("%s movers: %d of 6000 steps clear, %d contacts\n", fast ? "fast" : "slow", clear, contacts);
    EXPECT_GT(contacts, 50);
    if (!fast) {
      EXPECT_GT(clear, 1000);
    }
  }
}

TEST(WorldMoverIndex, AFastMoverIsFoundAtTheTimeOfImpactOfAVisitOfEveryMover) {
  // A crate crossing at 25 m/s (2.5 m a step) towards an agent standing in its way, every step of its run.
  MapSpec spec = testing::empty_spec(Vec3(40, 10, 10), 0.5);
  spec.movers.push_back(path(Vec3(2, 5, 5), Vec3(38, 5, 5), 25.0, kCrate));
  for (int k = 0; k < 50; ++k) spec.movers.push_back(orbit(Vec3(20, 5, 5), 3.0, 4.0 + k * 0.1, k * 0.3, kBall));
  const auto t = testing::build(spec)->movers_until(3.0);
  int hits = 0;
  for (int k = 0; k < 28; ++k) {
    const Vec3 agent(12, 5, 5);
    const auto a = t->first_contact(agent, agent + Vec3(1, 0, 0), 0.25, 0.1 * k, 0.1);
    ASSERT_TRUE(same(a, t->first_contact_scan(agent, agent + Vec3(1, 0, 0), 0.25, 0.1 * k, 0.1))) << k;
    hits += a.has_value() && a->obstacle_id == 0;
  }
  EXPECT_GE(hits, 1);
}

TEST(WorldMoverIndex, OfEquallyNearOrEquallyEarlyMoversTheLowestIndexWins) {
  // Twenty copies of one orbit and one path: every query ties between them.
  MapSpec spec = testing::empty_spec(Vec3(30, 30, 15), 0.5);
  for (int k = 0; k < 20; ++k) {
    spec.movers.push_back(k % 2 ? orbit(Vec3(15, 15, 7), 5.0, 8.0, 1.0, kBall) : path(Vec3(3, 3, 3), Vec3(27, 27, 12), 4.0, kCrate));
  }
  // And pairs mirrored about x = 15 (exactly equal distances from any point of that plane), the higher index on
  // either side.
  for (int k = 0; k < 10; ++k) {
    const double y = 2 + 2.5 * k, off = 2 + 0.5 * k;
    const Vec3 left(15 - off, y, 7), right(15 + off, y, 7);
    spec.movers.push_back(path(k % 2 ? left : right, (k % 2 ? left : right) + Vec3(0, 0, 4), 1.0, kBall));
    spec.movers.push_back(path(k % 2 ? right : left, (k % 2 ? right : left) + Vec3(0, 0, 4), 1.0, kBall));
  }
  const auto t = testing::build(spec)->movers_until(5.0);
  for (int k = 0; k < 10; ++k) {
    for (int q = 0; q < 20; ++q) {
      const Vec3 p(15, 2 + 2.5 * k, 6 + 0.3 * q);
      const MoverPoint a = t->nearest(p, 0.2 * q, 30.0);
      ASSERT_TRUE(same(a, t->nearest_scan(p, 0.2 * q, 30.0))) << k << " " << q;
      ASSERT_NE(a.mover, 21 + 2 * k) << k << " " << q;  // of the mirrored pair, never the higher index
      ASSERT_TRUE(same(t->nearest(p, 0.2 * q, 30.0, 21 + 2 * k), a)) << k << " " << q;  // not even as the hint
    }
  }
  for (int q = 0; q < 100; ++q) {
    const Vec3 p(5 + 0.2 * q, 10, 3 + 0.05 * q);
    const MoverPoint a = t->nearest(p, 0.04 * q, 30.0);
    ASSERT_TRUE(same(a, t->nearest_scan(p, 0.04 * q, 30.0))) << q;
    const auto c = t->first_contact(p, Vec3(15, 15, 7), 0.25, 0.04 * q, 0.1);
    ASSERT_TRUE(same(c, t->first_contact_scan(p, Vec3(15, 15, 7), 0.25, 0.04 * q, 0.1))) << q;
    if (c) {
      ASSERT_LE(c->obstacle_id, 1) << q;
    }
  }
}

TEST(WorldMoverIndex, BodiesAtRestAreStoredOnceAndTheBudgetHoldsTheWorstCase) {
  const auto arena = testing::build(crowded());
  const auto t = arena->movers_until(30.0);
  EXPECT_EQ(t->stats().blocks_simulated, 0u);  // nothing until a query reaches it
  (void)t->pose(250, 1.0);
  // The windows up to 1 s (4 blocks a second, 4 blocks a window: 1 s is the first block of the second), not one more.
  EXPECT_EQ(t->stats().blocks_simulated, 2 * MoverTimeline::kWindowBlocks);
  t->simulate_all();
  const TimelineStats s = t->stats();
  std::printf("%zu of %zu body-blocks at rest, %.1f MiB held of a worst case of %.1f MiB, simulated in %.3f s\n",
              s.resting_entries, s.resting_entries + s.moving_entries, s.bytes / 1048576.0,
              s.worst_case_bytes / 1048576.0, s.simulate_seconds);
  EXPECT_GT(s.resting_entries, s.moving_entries);  // dropped bodies settle within seconds
  EXPECT_LT(s.bytes, s.worst_case_bytes / 2);
  // A resting body's pose does not change to the bit.
  const Pose a = t->pose(250, 25.0), b = t->pose(250, 29.0);
  EXPECT_EQ(a.position, b.position);
  // Past the budget: refused, naming the setting that fits it, before anything is simulated.
  MapSpec spec = crowded();
  spec.movers.resize(200);
  for (int k = 0; k < 1600; ++k) spec.movers.push_back(body(Vec3(1.5 + (k % 27), 1.5 + (k / 27 % 27), 2.0 + k / 729), kBall));
  const auto big = testing::build(spec);
  try {
    (void)big->movers_until(100.0);
    FAIL() << "a timeline over its budget was accepted";
  } catch (const MapError& e) {
    EXPECT_EQ(e.field(), "physics.keyframe_hz");
    EXPECT_NE(std::string(e.what()).find("MiB"), std::string::npos) << e.what();
  }
  spec.physics.keyframe_hz = 10;
  EXPECT_NO_THROW((void)testing::build(spec)->movers_until(100.0));
}

// A map that sets no keyframe rate runs: the timeline keeps every substep when that fits its budget, else the
// highest rate dividing rate_hz that does (the next higher one would not), and its poses are those of a map
// that asks for that rate. Below kMinChosenKeyframeHz it refuses, naming physics.keyframe_hz.
TEST(WorldMoverIndex, AMapThatSetsNoKeyframeRateGetsTheHighestThatFits) {
  MapSpec spec = crowded();
  spec.physics.keyframe_hz.reset();
  const auto arena = testing::build(spec);
  const double duration = 6.0;
  const std::size_t every = MoverTimeline::worst_case_bytes(spec, duration, 1);
  for (const double share : {1.0, 0.6, 0.3, 0.13}) {
    const auto budget = static_cast<std::size_t>(share * double(every));
    const MoverTimeline t(arena->map(), arena->meshes(), duration, budget);
    const int stride = t.keyframe_stride();
    EXPECT_TRUE(t.stats().keyframe_hz_chosen);
    EXPECT_EQ(spec.physics.rate_hz % stride, 0) << share;
    EXPECT_LE(MoverTimeline::worst_case_bytes(spec, duration, stride), budget) << share;
    for (int finer = stride - 1; finer >= 1; --finer) {
      if (spec.physics.rate_hz % finer == 0) {
        EXPECT_GT(MoverTimeline::worst_case_bytes(spec, duration, finer), budget) << share << ": " << finer << " fits";
      }
    }
    if (share == 1.0) {
      EXPECT_EQ(stride, 1);
    } else {
      EXPECT_GT(stride, 1);
    }
    // The same motion as the map that asks for the chosen rate, to the bit.
    MapSpec asked = spec;
    asked.physics.keyframe_hz = spec.physics.rate_hz / stride;
    const auto asked_arena = testing::build(asked);
    const MoverTimeline u(asked_arena->map(), asked_arena->meshes(), duration);
    EXPECT_FALSE(u.stats().keyframe_hz_chosen);
    for (int m = 200; m < 300; m += 7) {
      for (const double at : {0.3, 1.77, 5.9}) {
        const Pose a = t.pose(m, at), b = u.pose(m, at);
        ASSERT_EQ(0, std::memcmp(a.position.data(), b.position.data(), 3 * sizeof(double))) << m << " at " << at;
      }
    }
  }
  // 10 keyframes a second would need more than this: refused, as a map that asks for a rate over budget is.
  const std::size_t lowest = MoverTimeline::worst_case_bytes(spec, duration, spec.physics.rate_hz / MoverTimeline::kMinChosenKeyframeHz);
  try {
    MoverTimeline(arena->map(), arena->meshes(), duration, lowest - 1);
    FAIL() << "a timeline over its budget at every rate it may choose was accepted";
  } catch (const MapError& e) {
    EXPECT_EQ(e.field(), "physics.keyframe_hz");
    EXPECT_NE(std::string(e.what()).find("even at 10 keyframes/s"), std::string::npos) << e.what();
  }
  EXPECT_EQ(MoverTimeline(arena->map(), arena->meshes(), duration, lowest).keyframe_stride(), 24);
}

TEST(WorldMoverIndex, ThinnedKeyframesAreTheSimulatedPosesOfThoseInstants) {
  const auto every = testing::build(crowded())->movers_until(4.0);
  const auto thinned = testing::build(crowded(30))->movers_until(4.0);  // every 8th substep of 240
  EXPECT_EQ(thinned->keyframe_stride(), 8);
  double error = 0.0, worst_ratio = 0.0;
  for (int m = 200; m < 300; ++m) {
    for (int k = 0; k < 4 * 30; ++k) {
      const double at = k * 8.0 / 240.0;
      // The same substep of the same simulation (up to the last bits of reading a time back as a keyframe).
      ASSERT_LT((every->pose(m, at).position - thinned->pose(m, at).position).norm(), 1e-9) << "mover " << m << " keyframe " << k;
      // Half way to the next keyframe the motion is interpolated: off the simulated point by at most half the
      // path the body ran between the two keyframes (where it changed course: an impact).
      const double between = at + 4.0 / 240.0;
      const double off = (every->pose(m, between).position - thinned->pose(m, between).position).norm();
      const double path = every->travel_bound(m, at, at + 8.0 / 240.0);
      error = std::max(error, off);
      if (path > 0.0) worst_ratio = std::max(worst_ratio, off / path);
      ASSERT_LE(off, 0.5 * path + 1e-9) << "mover " << m << " keyframe " << k;
    }
  }
  std::printf("interpolated against simulated motion, half way between keyframes: up to %.3f m, %.2f of the path\n",
              error, worst_ratio);
}

TEST(WorldMoverIndex, QueriesFromSeveralThreadsSimulateOnceAndAgree) {
  const auto arena = testing::build(crowded());
  const auto t = arena->movers_until(6.0);
  std::vector<MoverPoint> out[2];
  {
    std::vector<std::jthread> threads;
    for (int k = 0; k < 2; ++k) {
      threads.emplace_back([&, k] {
        for (int q = 0; q < 600; ++q) out[k].push_back(t->nearest(Vec3(15, 15, 1 + q % 10), 0.01 * q, 5.0));
      });
    }
  }
  for (int q = 0; q < 600; ++q) EXPECT_TRUE(same(out[0][std::size_t(q)], out[1][std::size_t(q)])) << q;
  const auto fresh = testing::build(crowded())->movers_until(6.0);
  for (int q = 0; q < 600; q += 37) EXPECT_TRUE(same(out[0][std::size_t(q)], fresh->nearest(Vec3(15, 15, 1 + q % 10), 0.01 * q, 5.0)));
}

}  // namespace
}  // namespace peg3d::world
