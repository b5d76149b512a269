// Push mode's world (world/bodies/push_world.hpp): agents as kinematic spheres push the pushable bodies as Bullet
// resolves the contact, with the analytic answers of a hit at any phase of a substep (head-on, oblique, 3-D),
// of a ball meeting a ball and of sliding friction; solid bodies stop an agent and are not moved by it; agents
// that touch nothing change no body's motion, to the bit; the world is a function of its inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>

#include "world/arena.hpp"
#include "world/bodies/body_physics.hpp"
#include "world/bodies/mover_timeline.hpp"
#include "world/bodies/push_world.hpp"
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

const Shape kPushedBall{Shape::Kind::kSphere, 0.5, 1.0, Vec3::Ones()};
const Shape kPushedCrate{Shape::Kind::kBox, 1.0, 1.0, Vec3(1.0, 1.0, 1.0)};

// A hit of a resting ball by an agent driving at constant velocity. The ball's surface is met at `phase` of a
// physics substep (0: on a substep boundary), in the last substep of a game step, after which the agent stands.
struct Hit {
  int rate_hz = 240;
  double restitution = 0.0;
  Vec3 travel = Vec3::UnitX();  ///< unit, the agent's direction
  Vec3 normal = Vec3::UnitX();  ///< unit, from the agent's centre towards the ball's at the touch
  double speed = 2.0;           ///< m/s
  double agent_radius = 0.5, ball_radius = 0.5;
  double phase = 0.0;
};

struct Flight {
  Vec3 velocity = Vec3::Zero();  ///< m/s, the ball's, over its free flight
  std::size_t pushes = 0;
};

Flight play(const Hit& h) {
  MapSpec spec = testing::empty_spec(Vec3(40, 40, 40), 1.0);
  spec.physics.gravity = Vec3::Zero();
  spec.physics.rate_hz = h.rate_hz;
  const Vec3 ball(20, 20, 20);
  spec.movers.push_back(body(ball, Shape{Shape::Kind::kSphere, h.ball_radius, 1.0, Vec3::Ones()},
                             DynamicMotion::Touch::kPushable));
  spec.movers.back().dynamic.restitution = h.restitution;
  spec.movers.back().dynamic.friction = 0.0;
  const auto arena = Arena::build(spec);
  const int substeps = static_cast<int>(std::lround(kDt * h.rate_hz));
  const int drive = 4;  // the touch falls in the last substep of step 4 (0-based)
  const double touch = drive * kDt + (substeps - 1 + h.phase) / h.rate_hz;
  Vec3 at = ball - (h.agent_radius + h.ball_radius) * h.normal - h.speed * touch * h.travel;
  PushWorld w(arena->map(), arena->physics_shapes(), substeps);
  w.add_agent(h.agent_radius, at);
  std::vector<Contact> touches;
  std::vector<Vec3> flight;
  for (int k = 0; k < drive + 12; ++k) {
    std::array<Vec3, 1> a{at}, b{k <= drive ? Vec3(at + h.speed * kDt * h.travel) : at};
    w.advance(a, b, touches);
    at = b[0];
    flight.push_back(w.pose(0).position);
  }
  return {(flight.back() - flight[flight.size() - 6]) / (5 * kDt), touches.size()};
}

// A resting ball of restitution e hit by an agent (a kinematic body: infinite mass) leaves along the contact
// normal n at (1 + e)(v . n), whatever the phase of the substep the touch falls in, head-on and oblique, in
// 3-D, at two physics rates and several speeds. Zero gravity, no friction: nothing but the hit moves it. In
// the agent's frame the ball's speed never grows (e <= 1: the hit gains no energy). The contact is found
// after the touch, with the agent up to a substep's travel deeper: its normal then leans by up to
// (v h sin angle) / (r + R) rad, which moves the answer by at most that over cos(angle) (1.0 % here).
TEST(PushWorld, AHitLeavesAlongTheNormalAtOnePlusETimesTheNormalSpeedAtEveryPhase) {
  const Vec3 skew = Vec3(1.0, -0.4, 0.3).normalized();
  const std::array<Hit, 4> shapes{{
      {.travel = Vec3::UnitX(), .normal = Vec3::UnitX(), .speed = 2.0},  // head-on
      {.travel = Vec3::UnitX(), .normal = Vec3(std::cos(0.52), std::sin(0.52), 0.0), .speed = 1.5},  // 30 degrees
      {.travel = skew, .normal = Vec3(1.0, 0.5, 0.8).normalized(), .speed = 2.0, .agent_radius = 0.3,
       .ball_radius = 0.6},  // 3-D, 47 degrees
      {.travel = Vec3(-1, 1, 1).normalized(), .normal = Vec3(-1, 1, 1).normalized(), .speed = 3.5},  // 3-D head-on
  }};
  for (const int rate : {240, 300}) {
    for (const double e : {0.0, 0.5, 1.0}) {
      for (const Hit& shape : shapes) {
        for (int p = 0; p <= 10; ++p) {
          Hit h = shape;
          h.rate_hz = rate;
          h.restitution = e;
          h.phase = p < 10 ? 0.1 * p : 0.99;
          const Flight f = play(h);
          const Vec3 expected = (1.0 + e) * h.speed * h.travel.dot(h.normal) * h.normal;
          std::ostringstream where;
          where << "rate " << rate << " e " << e << " normal (" << h.normal.transpose() << ") phase " << h.phase;
          EXPECT_GE(f.pushes, 1u) << where.str();
          EXPECT_LE((f.velocity - expected).norm(), 0.02 * expected.norm())
              << where.str() << ": leaves at " << f.velocity.transpose() << ", expected " << expected.transpose();
          const double before = h.speed * h.speed, after = (f.velocity - h.speed * h.travel).squaredNorm();
          EXPECT_LE(after, before * (1.0 + 1e-9)) << where.str();
        }
      }
    }
  }
}

// A ball of restitution 1 launched by an agent meets an equal ball of restitution 1 at rest: head-on it hands
// over its velocity and stops; off-centre the pair shares it as an elastic collision of equal masses does (at
// right angles); either way the pair's kinetic energy stays what it was. With restitution 0.5 and 0 the pair
// loses energy. The meeting falls at ten phases of a substep (the gap grows by a tenth of the ball's travel in
// a substep), at two physics rates.
TEST(PushWorld, ABallMeetingARestingBallGainsNoEnergyAtAnyPhase) {
  for (const int rate : {240, 300}) {
    for (const double e : {1.0, 0.5, 0.0}) {
      for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(0, 0.35, -0.25)}) {
        for (int p = 0; p < 10; ++p) {
          const double v = 2.0, launch = (1.0 + e) * v;
          const int substeps = static_cast<int>(std::lround(kDt * rate));
          MapSpec spec = testing::empty_spec(Vec3(40, 40, 40), 1.0);
          spec.physics.gravity = Vec3::Zero();
          spec.physics.rate_hz = rate;
          const Vec3 a0(10, 20, 20);
          const double gap = 1.3 + 0.1 * p * launch / rate;
          for (const Vec3& at : {a0, Vec3(a0 + Vec3(2 * kPushedBall.radius + gap, 0, 0) + offset)}) {
            spec.movers.push_back(body(at, kPushedBall, DynamicMotion::Touch::kPushable));
            spec.movers.back().dynamic.restitution = e;
            spec.movers.back().dynamic.friction = 0.0;
          }
          const auto arena = Arena::build(spec);
          PushWorld w(arena->map(), arena->physics_shapes(), substeps);
          Vec3 at = a0 - Vec3(2 * kPushedBall.radius + 0.37 * v / rate + 3 * v * kDt, 0, 0);
          w.add_agent(kPushedBall.radius, at);
          std::vector<Contact> touches;
          std::vector<Vec3> a, b;
          for (int k = 0; k < 20; ++k) {
            // The agent drives into ball 0 (in step 3) and stands from the step after.
            std::array<Vec3, 1> from{at}, to{k <= 3 ? Vec3(at + v * kDt * Vec3::UnitX()) : at};
            w.advance(from, to, touches);
            at = to[0];
            a.push_back(w.pose(0).position);
            b.push_back(w.pose(1).position);
          }
          std::ostringstream where;
          where << "rate " << rate << " e " << e << " offset (" << offset.transpose() << ") phase " << p;
          ASSERT_GE(touches.size(), 1u) << where.str();
          ASSERT_EQ(touches[0].obstacle_id, 0) << where.str();
          // Ball 0 flies free for two steps after the launch, before it can reach ball 1.
          const Vec3 va = (a[5] - a[4]) / kDt;
          EXPECT_LE((va - launch * Vec3::UnitX()).norm(), 0.02 * launch) << where.str();
          ASSERT_LT((b[5] - b.front()).norm(), 1e-12) << where.str() << ": ball 1 moved before the meeting";
          const Vec3 ua = (a[19] - a[14]) / (5 * kDt), ub = (b[19] - b[14]) / (5 * kDt);
          const double before = va.squaredNorm(), after = ua.squaredNorm() + ub.squaredNorm();
          EXPECT_LE(after, before * (1.0 + 1e-9)) << where.str();
          if (e == 1.0) {
            EXPECT_GE(after, before * (1.0 - 1e-6)) << where.str() << ": an elastic meeting keeps the energy";
            EXPECT_LT(std::abs(ua.dot(ub)), 1e-6 * before) << where.str() << ": equal masses part at right angles";
            if (offset.norm() == 0.0) {
              EXPECT_LE(ua.norm(), 0.02 * va.norm()) << where.str();
              EXPECT_LE((ub - va).norm(), 0.02 * va.norm()) << where.str();
            }
          }
        }
      }
    }
  }
}

// A crate pushed along the floor, then left alone, slides decelerating at mu g.
TEST(PushWorld, PushedCrateDeceleratesAtMuG) {
  for (const double mu : {0.2, 0.4}) {
    MapSpec spec = testing::empty_spec(Vec3(40, 10, 10), 0.5);
    spec.movers.push_back(body(Vec3(6, 5, 0.9), kPushedCrate, DynamicMotion::Touch::kPushable));
    spec.movers.back().dynamic.friction = mu;
    const auto arena = Arena::build(spec);
    PushWorld w(arena->map(), arena->physics_shapes(), kSubsteps);
    const double z = 0.5;  // the agent's centre at the crate's half height: a horizontal push
    w.add_agent(0.4, Vec3(4.5, 5, z));
    std::vector<Contact> touches;
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
    // While it slides (after the push, before it stops), the speed drops by mu g per second: the least-squares
    // slope of the speed over every step of the slide (a two-step difference swings by several percent).
    std::vector<std::pair<double, double>> slide;  // (s, m/s)
    for (int k = 20; k + 1 < static_cast<int>(crate.size()); ++k) {
      const double v = (crate[std::size_t(k + 1)] - crate[std::size_t(k)]).head<2>().norm() / kDt;
      if (v < 0.3) break;
      slide.emplace_back(k * kDt, v);
    }
    ASSERT_GE(slide.size(), 4u) << "mu " << mu;
    double mt = 0, mv = 0;
    for (const auto& [t, v] : slide) mt += t / slide.size(), mv += v / slide.size();
    double tv = 0, tt = 0;
    for (const auto& [t, v] : slide) tv += (t - mt) * (v - mv), tt += (t - mt) * (t - mt);
    const double deceleration = -tv / tt;
    // Within 6 %: a box sliding on a plane in Bullet alone (launched at 240 Hz, no peg3d) decelerates 3.6 to
    // 3.9 % above mu g, with Bullet's default contacts or split impulse. This crate, landed from 0.4 m and
    // pushed, measured +5.1 % (mu 0.2) and +4.0 % (mu 0.4) with push mode's split impulse, +3.6 % and +3.0 %
    // with Bullet's default.
    EXPECT_NEAR(deceleration, mu * 9.81, 0.06 * mu * 9.81) << "mu " << mu;
  }
}

// A solid body stops the agent, which does not move it; the touch is reported once, solid.
TEST(PushWorld, SolidBodyStopsTheAgentAndIsNotPushed) {
  MapSpec spec = testing::empty_spec(Vec3(40, 10, 10), 0.5);
  spec.physics.gravity = Vec3::Zero();
  spec.movers.push_back(body(Vec3(8, 5, 5), kPushedBall, DynamicMotion::Touch::kSolid));
  const auto arena = Arena::build(spec);
  PushWorld w(arena->map(), arena->physics_shapes(), kSubsteps);
  w.add_agent(0.5, Vec3(5, 5, 5));
  std::vector<Contact> touches;
  Vec3 at(5, 5, 5);
  for (int k = 0; k < 30; ++k) {
    std::array<Vec3, 1> a{at}, b{Vec3(at + Vec3(0.2, 0, 0))};
    w.advance(a, b, touches);
    at = b[0];
  }
  ASSERT_FALSE(touches.empty());
  for (const Contact& t : touches) EXPECT_FALSE(t.pushed);
  EXPECT_EQ(w.pose(0).position, Vec3(8, 5, 5));
  // It stands a substep's travel or less short of the ball's surface.
  const double gap = (at - Vec3(8, 5, 5)).norm() - 1.0;
  EXPECT_GE(gap, -PushWorld::kTouchTolerance);
  EXPECT_LE(gap, 2 * 0.2 / kSubsteps + PushWorld::kTouchTolerance);  // found within a substep's travel, stopped a substep back
}

// With the agents far away, the bodies fall, bounce and settle exactly as in push mode's world without agents:
// an agent that touches nothing changes nothing. (Not as in the shared timeline, whose solver keeps Bullet's
// default: body_physics.hpp.)
TEST(PushWorld, AgentsThatTouchNothingLeaveTheBodiesAlone) {
  MapSpec spec = testing::empty_spec(Vec3(30, 30, 15), 0.5);
  for (int k = 0; k < 12; ++k) {
    spec.movers.push_back(body(Vec3(10 + 1.5 * (k % 4), 10 + 1.5 * (k / 4), 3 + 0.7 * k), k % 2 ? kPushedBall : kPushedCrate,
                               k % 3 ? DynamicMotion::Touch::kPushable : DynamicMotion::Touch::kSolid));
    spec.movers.back().dynamic.restitution = 0.4;
  }
  const auto arena = Arena::build(spec);
  BodyPhysics alone(arena->map(), arena->physics_shapes(), arena->map().movers, true);
  PushWorld w(arena->map(), arena->physics_shapes(), kSubsteps);
  w.add_agent(0.5, Vec3(28, 28, 13));
  std::vector<Contact> touches;
  const Vec3 at(28, 28, 13);
  const double h = 1.0 / spec.physics.rate_hz;
  bool moved = false;
  for (int k = 1; k <= 40; ++k) {
    std::array<Vec3, 1> a{at}, b{at};
    w.advance(a, b, touches);
    for (int j = 1; j <= kSubsteps; ++j) alone.step(((k - 1) * kSubsteps + j) * h, h);
    for (int m = 0; m < static_cast<int>(spec.movers.size()); ++m) {
      const Pose x = alone.pose(std::size_t(m)), y = w.pose(m);
      ASSERT_EQ(0, std::memcmp(x.position.data(), y.position.data(), 3 * sizeof(double))) << "mover " << m << " step " << k;
      ASSERT_EQ(0, std::memcmp(x.orientation.coeffs().data(), y.orientation.coeffs().data(), 4 * sizeof(double)));
      moved = moved || (y.position - spec.movers[std::size_t(m)].start).norm() > 0.1;
    }
  }
  EXPECT_TRUE(moved) << "the bodies fell";
  EXPECT_TRUE(touches.empty());
}

TEST(PushWorld, SameInputsSameBits) {
  MapSpec spec = testing::empty_spec(Vec3(30, 10, 10), 0.5);
  for (int k = 0; k < 6; ++k) spec.movers.push_back(body(Vec3(8 + 2 * k, 5, 0.5), kPushedBall, DynamicMotion::Touch::kPushable));
  const auto arena = Arena::build(spec);
  auto play = [&] {
    PushWorld w(arena->map(), arena->physics_shapes(), kSubsteps);
    w.add_agent(0.5, Vec3(5, 5, 0.5));
    std::vector<Contact> touches;
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
