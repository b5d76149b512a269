#include "players/scripted_policies.hpp"

#include <gtest/gtest.h>

#include "geometry/apollonius.hpp"

namespace peg3d::players {
namespace {

using namespace peg3d::game;

AgentView view_of(const KinematicState& self, const KinematicState& other, double vs, double vo) {
  AgentView v;
  v.self = self;
  v.other = other;
  v.self_speed = vs;
  v.other_speed = vo;
  v.arena = {{0, 0, 0}, {35, 35, 20}};
  v.percept.obstacle = {5.0, self.position, false};
  return v;
}

Vec3 after(const AgentView& v, const Steering& s) { return direction(steer(v.self.heading, s, kPi)); }

TEST(ScriptedPolicies, PurePursuitPointsAtTheTarget) {
  const AgentView v = view_of({{10, 10, 10}, {0.0, kPi / 2}}, {{12, 14, 9}, {}}, 1.1, 1.0);
  PurePursuit p;
  EXPECT_LT((after(v, p.act(v)) - Vec3(2, 4, -1).normalized()).norm(), 1e-9);
}

TEST(ScriptedPolicies, ApolloniusInterceptorAimsAtTheInterceptionPoint) {
  const KinematicState e{{20, 17, 10}, {kPi, kPi / 2}};  // flying -x: met at (13.05, 17, 10), inside the arena
  const AgentView v = view_of({{10, 10, 10}, {0.0, kPi / 2}}, e, 1.1, 1.0);
  ApolloniusInterceptor a;
  const auto x = interception_point(v.self.position, e.position, direction(e.heading), 1.0 / 1.1);
  ASSERT_TRUE(x.has_value());
  EXPECT_LT((after(v, a.act(v)) - (*x - v.self.position).normalized()).norm(), 1e-9);
}

TEST(ScriptedPolicies, ProportionalNavigationTurnsWithTheLineOfSight) {
  // Target crossing left to right ahead: the LOS rotates clockwise (seen from +z), so PN turns right.
  const AgentView v = view_of({{10, 10, 10}, {0.0, kPi / 2}}, {{20, 12, 10}, {-kPi / 2, kPi / 2}}, 1.1, 1.0);
  ProportionalNavigation pn(3.0);
  EXPECT_LT(pn.act(v).d_alpha, 0.0);
  // A target behind gets pure pursuit.
  const AgentView behind = view_of({{10, 10, 10}, {0.0, kPi / 2}}, {{0, 10, 10}, {}}, 1.1, 1.0);
  EXPECT_NEAR(std::abs(pn.act(behind).d_alpha), kPi, 1e-12);
}

TEST(ScriptedPolicies, FleeRunsAwayAndTurnsOffTheWalls) {
  FleeLineOfSight f;
  const AgentView open = view_of({{17, 17, 10}, {0.0, kPi / 2}}, {{10, 17, 10}, {}}, 1.0, 1.1);
  EXPECT_LT((after(open, f.act(open)) - Vec3::UnitX()).norm(), 1e-9);  // straight away in open space
  const AgentView near_wall = view_of({{34, 17, 10}, {0.0, kPi / 2}}, {{27, 17, 10}, {}}, 1.0, 1.1);
  EXPECT_LT(after(near_wall, f.act(near_wall)).x(), 0.5);  // the wall at x = 35 pushes back
}

TEST(ScriptedPolicies, FleeApolloniusHeadsForTheFarthestReachablePoint) {
  FleeApollonius f;
  const AgentView v = view_of({{17, 17, 10}, {0.0, kPi / 2}}, {{12, 17, 10}, {}}, 1.0, 1.1);
  const Vec3 d = after(v, f.act(v));
  EXPECT_GT(d.x(), 0.9);  // away from the pursuer along +x, in the middle of the arena
}

TEST(ScriptedPolicies, RandomWalkStaysWithinTheBoundAndIsSeeded) {
  RandomWalk a(SteeringConfig{}, 4), b(SteeringConfig{}, 4);
  const AgentView v = view_of({{17, 17, 10}, {}}, {{10, 17, 10}, {}}, 1.0, 1.1);
  for (int i = 0; i < 100; ++i) {
    const Steering s = a.act(v), t = b.act(v);
    EXPECT_LE(std::abs(s.d_alpha), kPi / 4);
    EXPECT_EQ(s.d_alpha, t.d_alpha);
    EXPECT_EQ(s.d_theta, t.d_theta);
  }
}

}  // namespace
}  // namespace peg3d::players
