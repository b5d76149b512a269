// Moving obstacles: scripted motion against hand-computed positions, Bullet's dynamic bodies against the
// analytic drop, rest and rolling, and the contact and distance queries the game asks.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "world/arena.hpp"
#include "world/map/map_rules.hpp"
#include "world/bodies/mover_timeline.hpp"
#include "world/map/movers.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

constexpr double kG = 9.81;

MoverSpec path_mover(std::vector<Vec3> waypoints, double speed, bool loop, double radius = 1.0) {
  MoverSpec m;
  m.shape = {Shape::Kind::kSphere, radius, 1.0, Vec3::Ones()};
  m.motion = MoverSpec::Motion::kPath;
  m.path = {std::move(waypoints), speed, loop};
  return m;
}

MoverSpec ball(const Vec3& at, double radius, double mass = 10.0) {
  MoverSpec m;
  m.shape = {Shape::Kind::kSphere, radius, 1.0, Vec3::Ones()};
  m.motion = MoverSpec::Motion::kDynamic;
  m.start = at;
  m.dynamic.mass = mass;
  return m;
}

TEST(WorldMovers, PathMoversAreWhereTheirRouteSaysAtAnyTime) {
  // (0,0,0) -> (10,0,0) -> (10,5,0) at 2 m/s; the loop closes with the 11.18 m segment back to the start.
  PathMotion loop{{Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(10, 5, 0)}, 2.0, true};
  EXPECT_LT((path_position(loop, 0.0) - Vec3(0, 0, 0)).norm(), 1e-9);
  EXPECT_LT((path_position(loop, 3.0) - Vec3(6, 0, 0)).norm(), 1e-9);
  EXPECT_LT((path_position(loop, 6.0) - Vec3(10, 2, 0)).norm(), 1e-9);
  const double closing = std::sqrt(125.0);
  const Vec3 back = Vec3(10, 5, 0) + (1.0 / closing) * Vec3(-10, -5, 0);  // 1 m into the closing segment
  EXPECT_LT((path_position(loop, 8.0) - back).norm(), 1e-9);
  const double cycle = (15.0 + closing) / 2.0;  // s
  EXPECT_LT((path_position(loop, cycle + 3.0) - Vec3(6, 0, 0)).norm(), 1e-9);
  PathMotion bounce = loop;
  bounce.loop = false;  // 15 m out, 15 m back
  EXPECT_LT((path_position(bounce, 10.0) - Vec3(10, 0, 0)).norm(), 1e-9);  // s = 20: 5 m back from the end
  EXPECT_LT((path_position(bounce, 7.5) - Vec3(10, 5, 0)).norm(), 1e-9);   // turning at the last waypoint
  EXPECT_LT((path_position(bounce, 15.0) - Vec3(0, 0, 0)).norm(), 1e-9);   // home again
  EXPECT_LT((path_position(bounce, 18.0) - Vec3(6, 0, 0)).norm(), 1e-9);   // and out once more
}

TEST(WorldMovers, TheExactRemainderIsTheLibrarysFmodToTheBit) {
  // Paths wrap their arc length with it: random magnitudes, exact multiples and their neighbours a few ulps
  // away (where the division rounds across a whole number), quotients up to 2^52, and x < y.
  const auto same = [](double x, double y) {
    const double a = exact_remainder(x, y), b = std::fmod(x, y);
    return std::memcmp(&a, &b, sizeof(double)) == 0;
  };
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> exponent(-30, 30), big(0, 52);
  long checked = 0;
  for (int i = 0; i < 2000000; ++i) {
    const double y = std::ldexp(mantissa(rng), exponent(rng));
    const double x = i % 2 == 0 ? std::ldexp(mantissa(rng), exponent(rng)) : y * std::ldexp(mantissa(rng), big(rng));
    ASSERT_TRUE(same(x, y)) << std::hexfloat << x << " mod " << y;
    ++checked;
  }
  for (int i = 0; i < 200000; ++i) {
    const double y = std::ldexp(mantissa(rng), exponent(rng));
    double x = y * std::floor(std::ldexp(mantissa(rng), big(rng) / 2));
    for (int k = 0; k < 4; ++k) x = std::nextafter(x, 0.0);
    for (int k = 0; k < 9; ++k, x = std::nextafter(x, 1e300)) ASSERT_TRUE(same(x, y)) << std::hexfloat << x << " mod " << y;
    checked += 9;
  }
  // What paths ask: arc lengths speed * t over game times and cycles of map routes.
  for (int k = 0; k < 100000; ++k) {
    const double t = k * 0.1, x = 1.75 * t, y = 2.0 * (3.0 + std::sqrt(2.0));
    ASSERT_TRUE(same(x, y)) << k;
  }
  EXPECT_TRUE(same(0.0, 3.0));
  EXPECT_TRUE(same(3.0, 3.0));
  EXPECT_GT(checked, 3000000);
}

TEST(WorldMovers, OrbitMoversAreWhereTheirCircleSaysAtAnyTime) {
  OrbitMotion o{Vec3(1, 2, 3), 2.0, 8.0, Vec3::UnitZ(), 0.0};
  EXPECT_LT((orbit_position(o, 0.0) - Vec3(3, 2, 3)).norm(), 1e-9);  // phase 0: +x
  EXPECT_LT((orbit_position(o, 2.0) - Vec3(1, 4, 3)).norm(), 1e-9);  // a quarter turn, counter-clockwise
  EXPECT_LT((orbit_position(o, 8.0) - Vec3(3, 2, 3)).norm(), 1e-9);
  o.axis = Vec3(2, 0, 0);  // about x: phase 0 is +y, then +z
  EXPECT_LT((orbit_position(o, 0.0) - Vec3(1, 4, 3)).norm(), 1e-9);
  EXPECT_LT((orbit_position(o, 2.0) - Vec3(1, 2, 5)).norm(), 1e-9);
  o.phase = kPi;
  EXPECT_LT((orbit_position(o, 0.0) - Vec3(1, 0, 3)).norm(), 1e-9);
}

TEST(WorldMovers, ADroppedBallTouchesTheFloorAtTheFreeFallTimeAndComesToRest) {
  MapSpec spec = testing::empty_spec(Vec3(10, 10, 20), 0.5);
  const double h = 10.0, r = 0.5;
  spec.movers.push_back(ball(Vec3(5, 5, h + r), r));
  const auto arena = testing::build(spec);
  const auto timeline = arena->movers_until(6.0);
  ASSERT_TRUE(timeline);
  const double substep = 1.0 / timeline->rate_hz();
  // The first substep at which the ball's bottom reaches the floor (within Bullet's 2 cm contact distance).
  double touch = -1.0;
  for (int k = 0; k <= 6 * timeline->rate_hz(); ++k) {
    const double t = k * substep;
    if (timeline->pose(0, t).position.z() - r <= 0.02) {
      touch = t;
      break;
    }
  }
  std::printf("touch at %.5f s (free fall %.5f s, substep %.5f s); rest at z = %.5f m\n", touch,
              std::sqrt(2.0 * h / kG), substep, timeline->pose(0, 6.0).position.z());
  EXPECT_NEAR(touch, std::sqrt(2.0 * h / kG), substep);
  EXPECT_NEAR(timeline->pose(0, 6.0).position.z(), r, 0.01);  // at rest on the floor
  EXPECT_NEAR(timeline->pose(0, 6.0).position.x(), 5.0, 1e-6);
}

TEST(WorldMovers, ABallRollsDownAnInclineAtFiveSeventhsOfGSinB) {
  // A plane through the arena inclined at b about the y axis (falling towards +x), a ball released on it:
  // rolling without slipping, it accelerates at (5/7) g sin b along the slope.
  const double b = 20.0 * kPi / 180.0, r = 0.5;
  MapSpec spec = testing::empty_spec(Vec3(35, 35, 20), 0.5);
  auto plane = std::make_shared<TriangleMesh>();
  const auto z_at = [&](double x) { return 15.0 - std::tan(b) * x; };
  plane->vertices = {Vec3(0, 0, z_at(0)), Vec3(35, 0, z_at(35)), Vec3(35, 35, z_at(35)), Vec3(0, 35, z_at(0))};
  plane->faces = {{0, 1, 2}, {0, 2, 3}};
  TerrainMesh entry;
  entry.imported = plane;
  spec.meshes.push_back(entry);
  const Vec3 normal(std::sin(b), 0.0, std::cos(b));
  const Vec3 start = Vec3(5, 17.5, z_at(5)) + (r + 1e-3) * normal;
  MoverSpec m = ball(start, r, 5.0);
  m.dynamic.friction = 1.0;
  m.dynamic.rolling_friction = 0.0;
  spec.movers.push_back(m);
  const auto arena = testing::build(spec);
  const auto timeline = arena->movers_until(2.0);
  const Vec3 down(std::cos(b), 0.0, -std::sin(b));
  // s(t) = a t^2 / 2 between 0.5 s and 1.5 s (the start lets the contact settle).
  const double s1 = (timeline->pose(0, 0.5).position - start).dot(down);
  const double s2 = (timeline->pose(0, 1.5).position - start).dot(down);
  const double a = 2.0 * (s2 - s1) / (1.5 * 1.5 - 0.5 * 0.5);
  const double expected = 5.0 / 7.0 * kG * std::sin(b);
  std::printf("rolling acceleration %.4f m/s^2, (5/7) g sin b = %.4f m/s^2\n", a, expected);
  EXPECT_NEAR(a, expected, 0.05 * expected) << "measured " << a << " m/s^2";
  // Sliding without rolling would give g sin b: clearly different.
  EXPECT_LT(a, 0.85 * kG * std::sin(b));
}

TEST(WorldMovers, AStandingSphereIsHitWhenTheMoverReachesItAndMissedByAHair) {
  // A ball of radius 1 crossing the arena along x at 20 m/s; the agent's sphere (0.25 m) stands at x = 12:
  // they touch when the mover's centre is at 10.75, at t = (10.75 - 2) / 20 = 0.4375 s.
  MapSpec spec = testing::empty_spec(Vec3(40, 10, 10), 0.5);
  spec.movers.push_back(path_mover({Vec3(2, 5, 5), Vec3(38, 5, 5)}, 20.0, false));
  const auto arena = testing::build(spec);
  const auto t = arena->movers_until(3.0);
  const Vec3 agent(12, 5, 5);
  const auto hit = t->first_contact(agent, agent, 0.25, 0.4, 0.1);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->obstacle_id, 0);
  EXPECT_NEAR(0.4 + hit->fraction * 0.1, 0.4375, 1e-5);
  EXPECT_NEAR(hit->point.x(), 11.75, 1e-3);
  EXPECT_LT((hit->normal - Vec3::UnitX()).norm(), 1e-3);
  EXPECT_FALSE(t->first_contact(agent, agent, 0.25, 0.3, 0.1).has_value());  // the step before: not yet
  // A millimetre beyond its reach, the mover passes: no step of the whole crossing touches.
  const Vec3 aside(12, 5 + 1.25 + 1e-3, 5);
  for (int k = 0; k < 20; ++k) EXPECT_FALSE(t->first_contact(aside, aside, 0.25, 0.1 * k, 0.1).has_value()) << k;
  // Closing head on at 20 m/s each way (4 m a step): still no tunnelling.
  const auto head_on = t->first_contact(Vec3(14, 5, 5), Vec3(12, 5, 5), 0.25, 0.4, 0.1);
  ASSERT_TRUE(head_on.has_value());
  // The mover at 2 + 20 t, the agent at 14 - 20 (t - 0.4): the gap 1.25 closes at 40 m/s from 0.4 s (4 m apart).
  EXPECT_NEAR(0.4 + head_on->fraction * 0.1, 0.4 + (14.0 - 10.0 - 1.25) / 40.0, 1e-5);
}

// An agent running in lockstep beside a mover at 300 m/s, a hair (1.5e-4 m) more than the contact tolerance
// apart: conservative advancement creeps by gap / closing = 1.5e-4 / 60 of the step, and would need 400 000
// steps to finish. At its bound it answers a contact where it last measured the agent apart (gave_up), never
// "no contact"; the same pair at 30 m/s needs 40 000 steps and finds, rightly, none.
TEST(WorldMovers, AContactSearchThatReachesItsBoundAnswersAContactWhereTheAgentWasApart) {
  for (const double speed : {300.0, 30.0}) {
    MapSpec spec = testing::empty_spec(Vec3(40, 10, 10), 0.5);
    spec.movers.push_back(path_mover({Vec3(2, 5, 5), Vec3(38, 5, 5)}, speed, false));
    const auto t = testing::build(spec)->movers_until(1.0);
    const double dt = 0.1, r = 0.25, gap = 1.5e-4;
    const Vec3 from(2, 5 + 1.0 + r + gap, 5), to = from + Vec3(speed * dt, 0, 0);
    const auto c = t->first_contact(from, to, r, 0.0, dt);
    const auto scan = t->first_contact_scan(from, to, r, 0.0, dt);
    if (speed == 30.0) {
      EXPECT_FALSE(c.has_value());
      EXPECT_FALSE(scan.has_value());
      continue;
    }
    ASSERT_TRUE(c.has_value());
    EXPECT_TRUE(c->gave_up);
    EXPECT_EQ(c->obstacle_id, 0);
    // About kMaxAdvancementSteps steps of gap / closing into the step (closing: both travel 30 m).
    EXPECT_NEAR(c->fraction, MoverTimeline::kMaxAdvancementSteps * gap / (2 * speed * dt), 1e-3);
    // There the agent stands apart from the mover, beyond the tolerance.
    const Vec3 at = from + c->fraction * (to - from);
    EXPECT_GT((at - t->pose(0, c->fraction * dt).position).norm() - 1.0 - r, MoverTimeline::kContactTolerance);
    EXPECT_NEAR(c->normal.y(), 1.0, 1e-9);
    ASSERT_TRUE(scan.has_value());
    EXPECT_TRUE(scan->gave_up);
    EXPECT_EQ(scan->fraction, c->fraction);
  }
}

TEST(WorldMovers, NearestPointIsExactForEveryShape) {
  MapSpec spec = testing::empty_spec(Vec3(20, 20, 20), 0.5);
  MoverSpec box = path_mover({Vec3(5, 5, 5), Vec3(15, 5, 5)}, 1.0, false);
  box.shape = {Shape::Kind::kBox, 1.0, 1.0, Vec3(2, 4, 6)};
  box.rotation_deg = Vec3(0, 0, 90);  // the box's x along world y
  MoverSpec cyl = path_mover({Vec3(10, 15, 5), Vec3(10, 15, 6)}, 1.0, false);
  cyl.shape = {Shape::Kind::kCylinder, 1.5, 4.0, Vec3::Ones()};
  spec.movers = {box, cyl};
  const auto t = testing::build(spec)->movers_until(2.0);
  // At t = 1 the box is at (6, 5, 5), its extents 4 (x) by 2 (y) by 6 (z): 1 m from (9, 5, 5).
  MoverPoint p = t->nearest(Vec3(9, 5, 5), 1.0, 10.0);
  EXPECT_EQ(p.mover, 0);
  EXPECT_NEAR(p.distance, 1.0, 1e-12);
  EXPECT_LT((p.point - Vec3(8, 5, 5)).norm(), 1e-12);
  // The cylinder at (10, 15, 6) at t = 1: 2 m above its top from (10, 15, 10).
  p = t->nearest(Vec3(10, 15, 10), 1.0, 10.0);
  EXPECT_EQ(p.mover, 1);
  EXPECT_NEAR(p.distance, 2.0, 1e-12);
  EXPECT_EQ(t->nearest(Vec3(10, 15, 10), 1.0, 1.5).mover, -1);  // beyond the cap: none
}

TEST(WorldMovers, MapsBuiltInCodeRefuseMoversThatCannotBe) {
  MapSpec spec = testing::empty_spec(Vec3(10, 10, 10), 0.5);
  spec.spheres.push_back({Vec3(5, 5, 5), 1.0});
  MapSpec bad = spec;
  bad.movers.push_back(ball(Vec3(5, 5, 6.2), 0.5));  // overlaps the sphere
  EXPECT_THROW(testing::build(bad), MapError);
  bad = spec;
  bad.movers.push_back(ball(Vec3(0.6, 0.6, 0.6), 0.5));  // holds the pursuer's start (0.5, 0.5, 0.5)
  EXPECT_THROW(testing::build(bad), MapError);
  bad = spec;
  bad.movers.push_back(path_mover({Vec3(2, 2, 2), Vec3(9.5, 2, 2)}, 1.0, false));  // leaves the arena
  EXPECT_THROW(testing::build(bad), MapError);
  bad = spec;
  MoverSpec heavy = ball(Vec3(2, 8, 8), 0.5, 0.0);  // no mass
  bad.movers.push_back(heavy);
  EXPECT_THROW(testing::build(bad), MapError);
}

}  // namespace
}  // namespace peg3d::world
