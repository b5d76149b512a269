// Push mode's world (world/push_world.hpp): agents as kinematic spheres push the pushable bodies as Bullet
// resolves the contact, with the analytic answers of a head-on hit and of sliding friction; solid bodies stop
// an agent and are not moved by it; with agents that touch nothing the bodies move as in the shared timeline,
// to the bit; the world is a function of its inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "world/arena.hpp"
#include "world/mover_timeline.hpp"
#include "world/push_world.hpp"
#include "world_test_support.hpp"

namespace peg3d::world {
namespace {

constexpr int kSubsteps = 24;  // a 0.1 s game step at 240 Hz
constexpr double kDt = 0.1;

MoverSpec body(const Vec3& at, const Shape& shape, DynamicMotion::Touch touch) {
  MoverSpec m;
  m.shape = shape;
  m.motion = MoverSpec::Motion::kDynamic;
  m.start = at;
  m.dynamic.mass = 2.0;
  m.dynamic.touch = touch;
  return m;
}

const Shape kBall{Shape::Kind::kSphere, 0.5, 1.0, Vec3::Ones()};
const Shape kCrate{Shape::Kind::kBox, 1.0, 1.0, Vec3(1.0, 1.0, 1.0)};

// A resting ball of restitution e, hit head-on by an agent at speed v (a kinematic body: infinite mass),
// leaves at (1 + e) v. Zero gravity, so nothing but the hit moves it.
TEST(PushWorld, HeadOnHitLeavesAtOnePlusETimesTheAgentsSpeed) {
  for (const double e : {0.0, 0.5, 0.9}) {
    MapSpec spec = testing::empty_spec(Vec3(40, 10, 10), 0.5);
    spec.physics.gravity = Vec3::Zero();
    spec.movers.push_back(body(Vec3(8, 5, 5), kBall, DynamicMotion::Touch::kPushable));
    spec.movers.back().dynamic.restitution = e;
    spec.movers.back().dynamic.friction = 0.0;
    const auto arena = Arena::build(spec);
    const double v = 2.0;
    // The agent drives into the ball for 3 s, then stands; the ball, faster than the agent once e > 0, flies off.
    PushWorld w(*arena, kSubsteps);
    w.add_agent(0.5, Vec3(5, 5, 5));
    std::vector<BodyTouch> touches;
    Vec3 at(5, 5, 5);
    std::vector<Vec3> ball;
    const int steps = 30;
    for (int k = 0; k < steps; ++k) {
      // After the hit the agent stops, so the ball's flight is free.
      const bool driving = touches.empty();
      std::array<Vec3, 1> a{at}, b{driving ? Vec3(at + Vec3(v * kDt, 0, 0)) : at};
      w.advance(a, b, touches);
      at = b[0];
      ball.push_back(w.pose(0).position);
    }
    ASSERT_FALSE(touches.empty()) << "e " << e;
    EXPECT_FALSE(touches.front().solid);
    // The ball's speed over the last steps of its free flight.
    const double speed = (ball[steps - 1] - ball[steps - 6]).norm() / (5 * kDt);
    EXPECT_NEAR(speed, (1.0 + e) * v, 0.02 * (1.0 + e) * v) << "e " << e;
    EXPECT_NEAR(ball.back().y(), 5.0, 1e-6);
    EXPECT_NEAR(ball.back().z(), 5.0, 1e-6);
  }
}

// A crate pushed along the floor, then left alone, slides decelerating at mu g.
TEST(PushWorld, PushedCrateDeceleratesAtMuG) {
  for (const double mu : {0.2, 0.4}) {
    MapSpec spec = testing::empty_spec(Vec3(40, 10, 10), 0.5);
    spec.movers.push_back(body(Vec3(6, 5, 0.9), kCrate, DynamicMotion::Touch::kPushable));
    spec.movers.back().dynamic.friction = mu;
    const auto arena = Arena::build(spec);
    PushWorld w(*arena, kSubsteps);
    const double z = 0.5;  // the agent's centre at the crate's half height: a horizontal push
    w.add_agent(0.4, Vec3(4.5, 5, z));
    std::vector<BodyTouch> touches;
    Vec3 at(4.5, 5, z);
    std::vector<Vec3> crate;
    // 2 s of pushing at 3 m/s (the crate settles on the floor first: it starts touching it), then the agent backs off.
    for (int k = 0; k < 40; ++k) {
      const Vec3 to = k < 20 ? Vec3(at + Vec3(0.3, 0, 0)) : Vec3(at - Vec3(0.3, 0, 0));
      std::array<Vec3, 1> a{at}, b{to};
      w.advance(a, b, touches);
      at = b[0];
      crate.push_back(w.pose(0).position);
    }
    ASSERT_FALSE(touches.empty());
    // While it slides (after the push, before it stops), the speed drops by mu g per second.
    const auto speed = [&](int k) { return (crate[std::size_t(k + 1)] - crate[std::size_t(k)]).head<2>().norm() / kDt; };
    const double v1 = speed(21), v2 = speed(23);
    ASSERT_GT(v2, 0.1) << "mu " << mu;
    const double deceleration = (v1 - v2) / (2 * kDt);
    // Within 5 %: Bullet's own box sliding on a plane (launched, no agent) decelerates 0 to 5 % above mu g, its
    // normal impulses swinging with the penetration recovery.
    EXPECT_NEAR(deceleration, mu * 9.81, 0.05 * mu * 9.81) << "mu " << mu;
  }
}

// A solid body stops the agent, which does not move it; the touch is reported once, solid.
TEST(PushWorld, SolidBodyStopsTheAgentAndIsNotPushed) {
  MapSpec spec = testing::empty_spec(Vec3(40, 10, 10), 0.5);
  spec.physics.gravity = Vec3::Zero();
  spec.movers.push_back(body(Vec3(8, 5, 5), kBall, DynamicMotion::Touch::kSolid));
  const auto arena = Arena::build(spec);
  PushWorld w(*arena, kSubsteps);
  w.add_agent(0.5, Vec3(5, 5, 5));
  std::vector<BodyTouch> touches;
  Vec3 at(5, 5, 5);
  for (int k = 0; k < 30; ++k) {
    std::array<Vec3, 1> a{at}, b{Vec3(at + Vec3(0.2, 0, 0))};
    w.advance(a, b, touches);
    at = b[0];
  }
  ASSERT_FALSE(touches.empty());
  for (const BodyTouch& t : touches) EXPECT_TRUE(t.solid);
  EXPECT_EQ(w.pose(0).position, Vec3(8, 5, 5));
  // It stands a substep's travel or less short of the ball's surface.
  const double gap = (at - Vec3(8, 5, 5)).norm() - 1.0;
  EXPECT_GE(gap, -PushWorld::kTouchTolerance);
  EXPECT_LE(gap, 2 * 0.2 / kSubsteps + PushWorld::kTouchTolerance);  // found within a substep's travel, stopped a substep back
}

// With the agents far away, the bodies fall, bounce and settle exactly as in the shared timeline.
TEST(PushWorld, UntouchedBodiesMoveAsInTheSharedTimeline) {
  MapSpec spec = testing::empty_spec(Vec3(30, 30, 15), 0.5);
  for (int k = 0; k < 12; ++k) {
    spec.movers.push_back(body(Vec3(10 + 1.5 * (k % 4), 10 + 1.5 * (k / 4), 3 + 0.7 * k), k % 2 ? kBall : kCrate,
                               k % 3 ? DynamicMotion::Touch::kPushable : DynamicMotion::Touch::kSolid));
    spec.movers.back().dynamic.restitution = 0.4;
  }
  const auto arena = Arena::build(spec);
  const auto timeline = arena->movers_until(4.0);
  PushWorld w(*arena, kSubsteps);
  w.add_agent(0.5, Vec3(28, 28, 13));
  std::vector<BodyTouch> touches;
  const Vec3 at(28, 28, 13);
  for (int k = 1; k <= 40; ++k) {
    std::array<Vec3, 1> a{at}, b{at};
    w.advance(a, b, touches);
    for (int m = 0; m < timeline->count(); ++m) {
      const Pose x = timeline->pose(m, k * kDt), y = w.pose(m);
      // The timeline's pose at k dt interpolates its keyframes at a fraction one rounding off 1 or 0.
      ASSERT_LT((x.position - y.position).norm(), 1e-12) << "mover " << m << " step " << k;
    }
  }
  EXPECT_TRUE(touches.empty());
}

TEST(PushWorld, SameInputsSameBits) {
  MapSpec spec = testing::empty_spec(Vec3(30, 10, 10), 0.5);
  for (int k = 0; k < 6; ++k) spec.movers.push_back(body(Vec3(8 + 2 * k, 5, 0.5), kBall, DynamicMotion::Touch::kPushable));
  const auto arena = Arena::build(spec);
  auto play = [&] {
    PushWorld w(*arena, kSubsteps);
    w.add_agent(0.5, Vec3(5, 5, 0.5));
    std::vector<BodyTouch> touches;
    Vec3 at(5, 5, 0.5);
    for (int k = 0; k < 50; ++k) {
      std::array<Vec3, 1> a{at}, b{Vec3(at + Vec3(0.35, 0.01 * std::sin(k), 0))};
      w.advance(a, b, touches);
      at = b[0];
    }
    std::vector<Pose> poses;
    for (int m = 0; m < 6; ++m) poses.push_back(w.pose(m));
    return std::pair{poses, touches.size()};
  };
  const auto [p1, n1] = play();
  const auto [p2, n2] = play();
  EXPECT_GT(n1, 0u);
  EXPECT_EQ(n1, n2);
  for (int m = 0; m < 6; ++m) {
    EXPECT_EQ(0, std::memcmp(p1[m].position.data(), p2[m].position.data(), 3 * sizeof(double)));
    EXPECT_GT(p1[m].position.x(), 8 + 2 * m) << "every ball was pushed along";
  }
}

}  // namespace
}  // namespace peg3d::world
