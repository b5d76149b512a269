#include "game/game_config.hpp"
#include "game/percept.hpp"

#include <gtest/gtest.h>

namespace peg3d::game {
namespace {

const Box kArena{{0, 0, 0}, {35, 35, 20}};

// A hand-placed scene: the pursuer at (10, 10, 5) flying level along +x, the evader at (10, 20, 5) (to its
// left), a sphere obstacle whose nearest point is (12, 10, 5) (dead ahead, 2 m away).
TEST(Percept, HandPlacedScene) {
  AgentConfig pc = agent_preset("peg3d", Role::kPursuer);
  const KinematicState p{{10, 10, 5}, {0.0, kPi / 2}};
  const KinematicState e{{10, 20, 5}, {kPi / 2, kPi / 2}};
  const ObstacleSense field{2.0, {12, 10, 5}, true};
  const Percept q = perceive(Role::kPursuer, pc.observation, pc.radius, p, e, field, kArena, 5.0);
  EXPECT_DOUBLE_EQ(q.target_distance, 10.0);
  EXPECT_NEAR(q.target.azimuth, kPi / 2, 1e-12);  // turn left by 90 degrees
  EXPECT_NEAR(q.target.elevation, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(q.obstacle.distance, 2.0);
  EXPECT_NEAR(q.to_obstacle.azimuth, 0.0, 1e-12);  // dead ahead
  EXPECT_NEAR(q.to_obstacle.elevation, 0.0, 1e-12);
  EXPECT_FALSE(q.pinned);

  // The evader, flying along +y (away from the pursuer): its reference line is P->E, so fleeing reads 0.
  const AgentConfig ec = agent_preset("peg3d", Role::kEvader);
  const Percept qe = perceive(Role::kEvader, ec.observation, ec.radius, e, p, {5.0, e.position, false}, kArena, 5.0);
  EXPECT_NEAR(qe.target.azimuth, 0.0, 1e-12);
  // The paper measures it from E->P: fleeing reads pi.
  const Percept qp = perceive(Role::kEvader, agent_preset("paper", Role::kEvader).observation, ec.radius, e, p, {5.0, e.position, false},
                              kArena, 5.0);
  EXPECT_NEAR(std::abs(qp.target.azimuth), kPi, 1e-12);
}

TEST(Percept, TheOpponentsHeadingIsMeasuredFromTheLinePursuerToEvader) {
  // The pursuer at (10, 10, 5), the evader 10 m along +y. P->E is +y for both roles.
  AgentConfig pc = agent_preset("peg3d", Role::kPursuer);
  AgentConfig ec = agent_preset("peg3d", Role::kEvader);
  const KinematicState e{{10, 20, 5}, {kPi / 2 - 0.4, kPi / 2 + 0.2}};  // fleeing, 0.4 rad right, a little down
  // An interceptor leading by 0.3 rad to the left (towards +x is right of +y): azimuth pi/2 + 0.3, level.
  const KinematicState p{{10, 10, 5}, {kPi / 2 + 0.3, kPi / 2}};
  const ObstacleSense none{5.0, Vec3::Zero(), false};
  EXPECT_EQ(perceive(Role::kEvader, ec.observation, ec.radius, e, p, none, kArena, 5.0).opponent_heading.azimuth, 0.0);  // off: 0
  ec.observation.opponent_heading = pc.observation.opponent_heading = true;
  const Percept qe = perceive(Role::kEvader, ec.observation, ec.radius, e, p, none, kArena, 5.0);
  EXPECT_NEAR(qe.opponent_heading.azimuth, -0.3, 1e-12);  // from the pursuer's heading back to P->E
  EXPECT_NEAR(qe.opponent_heading.elevation, 0.0, 1e-12);
  const Percept qp = perceive(Role::kPursuer, pc.observation, pc.radius, p, e, none, kArena, 5.0);
  EXPECT_NEAR(qp.opponent_heading.azimuth, 0.4, 1e-12);  // from the evader's heading to P->E
  EXPECT_NEAR(qp.opponent_heading.elevation, -0.2, 1e-12);
  // A pure pursuer heading straight at the evader reads 0.
  const KinematicState pp{{10, 10, 5}, {kPi / 2, kPi / 2}};
  EXPECT_NEAR(perceive(Role::kEvader, ec.observation, ec.radius, e, pp, none, kArena, 5.0).opponent_heading.azimuth, 0.0, 1e-12);
}

TEST(Percept, BoundaryCountsAsObstacleWhenConfigured) {
  AgentConfig c = agent_preset("peg3d", Role::kPursuer);
  const KinematicState p{{10, 10, 1.5}, {0.0, kPi / 2}};  // 1.5 m above the floor
  const KinematicState e{{20, 10, 1.5}, {0.0, kPi / 2}};
  const ObstacleSense none{5.0, p.position, false};
  const Percept with = perceive(Role::kPursuer, c.observation, c.radius, p, e, none, kArena, 5.0);
  EXPECT_TRUE(with.obstacle.found);
  EXPECT_DOUBLE_EQ(with.obstacle.distance, 1.5);
  EXPECT_LT((with.obstacle.point - Vec3(10, 10, 0)).norm(), 1e-12);
  EXPECT_NEAR(with.to_obstacle.elevation, kPi / 2, 1e-12);  // straight down from level flight
  c.observation.boundary_is_obstacle = false;
  const Percept without = perceive(Role::kPursuer, c.observation, c.radius, p, e, none, kArena, 5.0);
  EXPECT_FALSE(without.obstacle.found);
  EXPECT_DOUBLE_EQ(without.obstacle.distance, 5.0);
  EXPECT_DOUBLE_EQ(without.to_obstacle.azimuth, kPi);  // nothing in range reads as behind
}

TEST(Percept, PinnedMeansWithinOneRadiusOfAFace) {
  EXPECT_TRUE(is_pinned({10, 10, 0.25}, 0.25, kArena));
  EXPECT_TRUE(is_pinned({34.8, 10, 5}, 0.25, kArena));
  EXPECT_FALSE(is_pinned({10, 10, 0.26}, 0.25, kArena));
  EXPECT_TRUE(is_pinned({10, 10, 0.1}, 0.05, kArena));  // at least 0.1 m
  EXPECT_FALSE(is_pinned({10, 10, 0.11}, 0.05, kArena));
}

}  // namespace
}  // namespace peg3d::game
