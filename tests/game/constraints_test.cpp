// The constraint layer, function by function, with answers worked out by hand.
#include "game/constraints.hpp"

#include <cmath>
#include <span>
#include <vector>

#include <gtest/gtest.h>

namespace peg3d::game {
namespace {

TEST(Constraints, BoundedSteeringClampsEachAngleAndTheClimb) {
  SteeringConfig s;  // pi/4 per step, no climb limit
  const Heading h{0.0, kPi / 2};
  const Heading a = bounded_steer(h, {2.0, -0.1}, s, 0.1);
  EXPECT_DOUBLE_EQ(a.alpha, kPi / 4);
  EXPECT_DOUBLE_EQ(a.theta, kPi / 2 - 0.1);
  s.polar_margin = kPi / 3;  // theta in [pi/3, 2pi/3]
  EXPECT_DOUBLE_EQ(bounded_steer(h, {0.0, -0.7}, s, 0.1).theta, kPi / 3);
  s.reading = SteeringReading::kPerSecond;  // pi/4 rad/s: at most pi/40 in 0.1 s
  EXPECT_DOUBLE_EQ(bounded_steer(h, {1.0, 0.0}, s, 0.1).alpha, kPi / 40);
}

TEST(Constraints, MotionSpacesAreThePapersCones) {
  const Vec3 p(0, 0, 0), e(10, 0, 0);
  const auto pc = motion_space(Role::kPursuer, p, e, 1.1, 1.0);
  ASSERT_TRUE(pc.has_value());
  EXPECT_TRUE(pc->axis.isApprox(Vec3::UnitX()));
  EXPECT_NEAR(pc->half_angle, std::asin(1.0 / 1.1), 1e-15);  // 65.38 degrees, eq. 6
  const auto ec = motion_space(Role::kEvader, e, p, 1.0, 1.1);  // the evader at e, its pursuer at p
  ASSERT_TRUE(ec.has_value());
  EXPECT_TRUE(ec->axis.isApprox(Vec3::UnitX()));  // away from the pursuer
  EXPECT_NEAR(ec->half_angle, kPi / 2, 1e-15);
  EXPECT_FALSE(motion_space(Role::kPursuer, p, p, 1.1, 1.0).has_value());
}

TEST(Constraints, KeepWithinProjectsOnlyWhatLiesOutside) {
  const Cone cone{Vec3::UnitX(), kPi / 4};
  Vec3 inside = Vec3(1, 0.5, 0).normalized();
  const Vec3 kept = inside;
  EXPECT_FALSE(keep_within(cone, inside, 0.0, Vec3::UnitX(), 0.0));
  EXPECT_EQ(inside, kept);
  Vec3 outside = Vec3::UnitY();
  EXPECT_TRUE(keep_within(cone, outside, 0.0, Vec3::UnitX(), 0.0));
  EXPECT_NEAR(angle_between(outside, Vec3::UnitX()), kPi / 4, 1e-12);  // onto the cone's surface
  EXPECT_NEAR(outside.z(), 0.0, 1e-12);                                // in the plane of d and the axis
}

TEST(Constraints, GuardConeWidensFromWarnToStopDistance) {
  const ObstacleGuard g;  // stop 0.8 m, warn 2 m
  const Vec3 at(0, 0, 0);
  const auto near = [&](double d) { return ObstacleSense{d, Vec3(d, 0, 0), true}; };
  EXPECT_FALSE(guard_cone(g, at, near(2.5)).has_value());  // beyond warn_distance
  const auto half = guard_cone(g, at, near(1.4));         // halfway: a quarter-turn cone excluded
  ASSERT_TRUE(half.has_value());
  EXPECT_TRUE(half->axis.isApprox(-Vec3::UnitX()));
  EXPECT_NEAR(half->half_angle, kPi - kPi / 4, 1e-12);
  EXPECT_NEAR(guard_cone(g, at, near(0.8))->half_angle, kPi / 2, 1e-12);  // at stop: never approach
  EXPECT_NEAR(guard_cone(g, at, near(0.3))->half_angle, kPi / 2, 1e-12);
  ObstacleGuard off = g;
  off.enabled = false;
  EXPECT_FALSE(guard_cone(off, at, near(0.5)).has_value());
  EXPECT_FALSE(guard_cone(g, at, ObstacleSense{0.5, Vec3::Zero(), false}).has_value());
}

TEST(Constraints, AgainstAFaceTheGuardTurnsTheMotionAlongIt) {
  // An obstacle up and ahead (+x +z): the guard allows x + z <= 0, and d = (0.6, 0.3, -0.8) is allowed. On
  // the floor the clamp removes its downward part, leaving (0.6, 0.3, 0), which approaches the obstacle:
  // within the floor it turns to the first allowed direction on the way to -x, which is +y.
  const Cone allowed{Vec3(-1, 0, -1).normalized(), kPi / 2};
  const Box box{Vec3(0.25, 0.25, 0.25), Vec3(34.75, 34.75, 19.75)};
  const Vec3 start = Vec3(0.6, 0.3, -0.8).normalized();
  ASSERT_TRUE(allowed.contains(start));
  Vec3 d = start;
  EXPECT_TRUE(guard_along_faces(allowed, d, Vec3(10, 10, 0.25), box, 0.0, heading_of(start)));
  EXPECT_NEAR(d.x(), 0.0, 1e-8);
  EXPECT_NEAR(d.y(), 1.0, 1e-8);
  EXPECT_NEAR(d.z(), 0.0, 1e-12);
  Vec3 free = start;  // away from every face the allowed direction stands
  EXPECT_FALSE(guard_along_faces(allowed, free, Vec3(10, 10, 5), box, 0.0, heading_of(start)));
  EXPECT_EQ(free, start);
}

TEST(Constraints, AgainstAWallWithTheObstacleAheadAlongItTheGuardLeavesTheWall) {
  // The forest case: a pursuer against the wall x = 34.75, flying along it (-y) at the 30 degree climb limit
  // towards a trunk 0.6 m ahead, inside stop_distance. Every allowed slide along the wall is steeper than the
  // limit, and the nearest one points straight up, where the azimuth is undefined: turning towards it kept
  // the heading, and the pursuer slid into the trunk. Now it turns off the wall, away from the trunk. The
  // first step's heading may still approach (a quarter turn at most per step), its motion may not.
  AgentConfig c = agent_preset("peg3d", Role::kPursuer);
  c.motion_space = false;
  const Box bounds = Box{Vec3::Zero(), Vec3(35, 35, 20)}.shrunk(c.radius);
  KinematicState self{Vec3(34.75, 10, 5), heading_of(Vec3(0.0, -std::sqrt(0.75), 0.5))};
  const Vec3 trunk(34.6, 9.4, 5);  // the nearest point of the trunk
  double before = (self.position - trunk).norm();
  for (int step = 0; step < 2; ++step) {
    const ObstacleSense sense{(self.position - trunk).norm(), trunk, true};
    const ConstraintInputs in{c, Role::kPursuer, 0.1, self, Vec3(20, 0, 5), 1.0, sense, bounds, nullptr};
    Vec3 moving;
    self.heading = constrained_heading(in, {0.0, 0.0}, &moving);
    EXPECT_GE(self.heading.theta, kPi / 3 - 1e-12);
    EXPECT_LE(self.heading.theta, 2 * kPi / 3 + 1e-12);
    EXPECT_LT(direction(self.heading).x(), -0.5) << "step " << step;  // off the wall
    self.position += 0.11 * moving;
    const double after = (self.position - trunk).norm();
    EXPECT_GE(after, before - 1e-12) << "step " << step;
    before = after;
  }
}

// A map of vertical trunks, sensed exactly: the guard's probe for the tests.
class Trunks final : public ObstacleProbe {
 public:
  struct Trunk {
    double x, y, radius;
  };
  explicit Trunks(std::vector<Trunk> trunks) : trunks_(std::move(trunks)) {}
  ObstacleSense nearest(const Vec3& p, double) const override {
    ObstacleSense best;
    for (const Trunk& t : trunks_) {
      const Vec3 axis(t.x, t.y, p.z());
      const double r = (p - axis).norm();
      const Vec3 point = r > 0.0 ? Vec3(axis + (p - axis) * (t.radius / r)) : axis;
      const double d = std::max(r - t.radius, 0.0);
      if (!best.found || d < best.distance) best = {d, point, true};
    }
    return best;
  }

 private:
  std::vector<Trunk> trunks_;
};

TEST(Constraints, TheLookAheadKeepsClearOfTheNextTrunkWhileSlidingPastTheNearest) {
  // The forest case: flying +x past trunk A (0.54 m to the side, the one the distance field reports as the
  // nearest) into trunk B, 0.40 m ahead. Guarding A alone lets it slide on into B; the look ahead (0.6 m
  // along the heading) finds B within stop_distance and turns the agent off it, still clear of A.
  AgentConfig c = agent_preset("peg3d", Role::kPursuer);
  c.motion_space = false;
  const Box bounds = Box{Vec3::Zero(), Vec3(35, 35, 20)}.shrunk(c.radius);
  const Trunks map({{5.8, 20.9, 0.3}, {6.45, 21.74, 0.25}});
  const KinematicState self{Vec3(5.8, 21.74, 3.4), Heading{0.0, kPi / 2}};
  const Vec3 a(5.8, 21.2, 3.4), b(6.2, 21.74, 3.4);  // the trunks' nearest points
  const ObstacleSense field{(self.position - a).norm(), a, true};
  ASSERT_NEAR(field.distance, 0.54, 1e-9);
  // The distance to B after each of two steps. Heading straight at B, the first step may still approach it
  // (a quarter turn at most per step); the second may not.
  const auto steps = [&](const ObstacleProbe* probe) {
    KinematicState k = self;
    std::vector<double> to_b;
    for (int step = 0; step < 2; ++step) {
      const ObstacleSense sensed = step == 0 ? field : ObstacleSense{(k.position - a).norm(), a, true};
      const ConstraintInputs in{c, Role::kPursuer, 0.1, k, Vec3(30, 5, 3), 1.0, sensed, bounds, probe};
      Vec3 moving;
      k.heading = constrained_heading(in, {0.0, 0.0}, &moving);
      k.position += 0.11 * moving;
      to_b.push_back((k.position - b).norm());
      EXPECT_GE((k.position - a).norm(), 0.54 - 0.11) << "step " << step;  // A stays guarded either way
    }
    return to_b;
  };
  const double start = (self.position - b).norm();
  const auto unguarded = steps(nullptr);  // the nearest only: on into B
  EXPECT_LT(unguarded[1], unguarded[0]);
  EXPECT_LT(unguarded[1], start - 0.15);
  const auto guarded = steps(&map);
  EXPECT_GE(guarded[1], guarded[0] - 1e-9);  // B is no longer approached
  c.guard.look_ahead = 0.0;  // off: as without a probe
  EXPECT_EQ(steps(&map), unguarded);
}

TEST(Constraints, KeepWithinBothMeetsTheSecondConeWhereTheFirstAllows) {
  // The first cone allows y >= 0, the second x <= 0; d = (1, 0.1, 0) lies in the first only. Its projection
  // into the second, (0, 1, 0), lies in the first too.
  const Cone first{Vec3::UnitY(), kPi / 2}, second{-Vec3::UnitX(), kPi / 2};
  Vec3 d = Vec3(1, 0.1, 0).normalized();
  EXPECT_TRUE(keep_within_both(first, second, d, 0.0, heading_of(d)));
  EXPECT_TRUE(d.isApprox(Vec3::UnitY(), 1e-12));
  // Where the projection leaves the first cone, the answer is where the surfaces cross. The first cone is
  // 60 degrees about (0.6, 0.8, 0): on the plane x = 0 its surface has 0.8 y = cos 60, so y = 0.625 and
  // z = +-0.781; the crossing nearer to e is the upper one.
  const Cone tilted{Vec3(0.6, 0.8, 0), kPi / 3};
  Vec3 e = Vec3(0.9, 0.1, 0.42).normalized();
  ASSERT_TRUE(tilted.contains(e));
  EXPECT_TRUE(keep_within_both(tilted, second, e, 0.0, heading_of(e)));
  EXPECT_NEAR(e.x(), 0.0, 1e-12);
  EXPECT_NEAR(e.y(), 0.625, 1e-12);
  EXPECT_NEAR(e.z(), std::sqrt(1 - 0.625 * 0.625), 1e-12);
  // Two cones that exclude each other: d stays (the first, the nearest obstacle's, has the last word).
  Vec3 f = Vec3(1, 1, 0).normalized();
  EXPECT_FALSE(keep_within_both(Cone{Vec3(1, 1, 0).normalized(), kPi / 8}, second, f, 0.0, heading_of(f)));
  EXPECT_TRUE(f.isApprox(Vec3(1, 1, 0).normalized()));
}

TEST(Constraints, ConstrainedHeadingTurnsWithinTheBoundAndTheGuardComesLast) {
  AgentConfig c = agent_preset("peg3d", Role::kPursuer);
  const KinematicState self{Vec3(5, 5, 5), Heading{0.0, kPi / 2}};  // flying along +x
  const Vec3 opponent(15, 5, 5);                                     // straight ahead
  ObstacleSense field;                                               // nothing near
  const Box bounds = Box{Vec3::Zero(), Vec3(35, 35, 20)}.shrunk(c.radius);
  const ConstraintInputs in{c, Role::kPursuer, 0.1, self, opponent, 1.0, field, bounds, nullptr};
  // Nothing in the way: the request, bounded.
  const Heading plain = constrained_heading(in, {0.3, 0.0});
  EXPECT_DOUBLE_EQ(plain.alpha, 0.3);
  // A request to turn right round leaves the cone; the agent turns back towards it by at most pi/4.
  const Heading back = constrained_heading(in, {kPi, 0.0});
  EXPECT_LE(std::abs(back.alpha), kPi / 4 + 1e-12);
  // An obstacle 0.5 m ahead (inside stop_distance): straight ahead is what the motion space wants, but the
  // guard forbids approaching it at all.
  field = ObstacleSense{0.5, Vec3(5.5, 5, 5), true};
  // The allowed half-space lies a quarter turn away; the agent turns towards it as far as one step allows.
  const Heading guarded = constrained_heading(in, {0.0, 0.0});
  EXPECT_NEAR(std::abs(guarded.alpha), kPi / 4, 1e-9);
  EXPECT_LE(direction(guarded).dot(Vec3::UnitX()), std::cos(kPi / 4) + 1e-9);
}

TEST(Constraints, WhenTheTurnBoundLeavesTheHeadingApproachingTheMotionHoldsOff) {
  // Flying straight at an obstacle 0.5 m ahead (inside stop_distance): the allowed half-space lies a quarter
  // turn away, one step turns only an eighth, so the heading still approaches. The guard's promise then holds
  // for the motion: its part towards the obstacle is removed and the agent slides past, slower. The forest's
  // two-trunk corners were where pursuers, turning too slowly, collided.
  AgentConfig c = agent_preset("peg3d", Role::kPursuer);
  c.motion_space = false;
  const KinematicState self{Vec3(5, 5, 5), Heading{0.0, kPi / 2}};
  const Box bounds = Box{Vec3::Zero(), Vec3(35, 35, 20)}.shrunk(c.radius);
  const ObstacleSense field{0.5, Vec3(5.5, 5, 5), true};
  const ConstraintInputs in{c, Role::kPursuer, 0.1, self, Vec3(15, 5, 5), 1.0, field, bounds, nullptr};
  Vec3 moving;
  const Heading h = constrained_heading(in, {0.0, 0.0}, &moving);
  EXPECT_NEAR(std::abs(h.alpha), kPi / 4, 1e-9);  // the heading turns as far as one step allows
  EXPECT_NEAR(moving.x(), 0.0, 1e-12);            // no approach
  EXPECT_NEAR(moving.y(), direction(h).y(), 1e-12);  // the rest of the motion is the heading's
  EXPECT_NEAR(moving.z(), direction(h).z(), 1e-12);
  EXPECT_GT(moving.y() * h.alpha, 0.0);              // sliding to the side it turns to

  // Beyond stop_distance the guard only turns (the cone is narrower than a half-space there): the motion is
  // the heading's direction, whole.
  const ObstacleSense farther{1.0, Vec3(6.0, 5, 5), true};
  const ConstraintInputs far_in{c, Role::kPursuer, 0.1, self, Vec3(15, 5, 5), 1.0, farther, bounds, nullptr};
  const Heading g = constrained_heading(far_in, {0.0, 0.0}, &moving);
  EXPECT_EQ(moving, direction(g));
}

TEST(Constraints, TheLastResortEndsNoStepNearerThanTheClearanceWhateverTheFieldNames) {
  // The forest case: between two trunks, the field's nearest voxel is trunk B's, behind the agent, while it
  // flies straight at trunk A, 0.30 m ahead (exact). Guarding B lets the step close 0.11 m on A, 0.06 m short
  // of a collision. With A among the exact points near it, the step ends radius + margin from A, not nearer.
  AgentConfig c = agent_preset("peg3d", Role::kPursuer);
  c.motion_space = false;
  const double step = c.speed * 0.1;
  ASSERT_NEAR(step, 0.11, 1e-12);
  const Box bounds = Box{Vec3::Zero(), Vec3(35, 35, 20)}.shrunk(c.radius);
  const KinematicState self{Vec3(5, 5, 5), Heading{0.0, kPi / 2}};
  const Vec3 a(5.30, 5, 5), b(4.45, 5.1, 5);
  const ObstacleSense field{(self.position - b).norm(), b, true};
  const std::vector<world::NearPoint> near{{.point = a, .distance = 0.30}, {.point = b, .distance = field.distance}};
  ASSERT_LT(0.30, hold_range(c, 0.1));
  const auto end_of_step = [&](std::span<const world::NearPoint> exact) {
    const ConstraintInputs in{c, Role::kPursuer, 0.1, self, Vec3(20, 5, 5), 1.0, field, bounds, nullptr, exact};
    Vec3 moving;
    const Heading h = constrained_heading(in, {0.0, 0.0}, &moving);
    EXPECT_NEAR(h.alpha, 0.0, 1e-12);  // away from B: the guard does not turn
    return advance(self, h, moving, c.speed, 0.1, bounds).position;
  };
  EXPECT_NEAR((end_of_step({}) - a).norm(), 0.30 - step, 1e-12);  // the field's guard alone: on into A
  const Vec3 held = end_of_step(near);
  EXPECT_NEAR((held - a).norm(), c.radius + kHoldMargin, 1e-12);  // up to the clearance, no nearer
  EXPECT_GT((held - b).norm(), field.distance);
}

TEST(Constraints, TheLastResortHoldsWhereTheClampMovesTheStep) {
  // Against the wall x = 34.75, sliding tangentially past a trunk's point that lies off the wall: the motion
  // keeps the clearance, but its part into the wall is what the clamp removes, and the rest closes on the
  // trunk. The last resort keeps the step clear as the clamp leaves it: inside the arena and the clearance.
  AgentConfig c = agent_preset("peg3d", Role::kPursuer);
  c.motion_space = false;
  const Box bounds = Box{Vec3::Zero(), Vec3(35, 35, 20)}.shrunk(c.radius);
  const Vec3 at(34.75, 10, 5), point(34.6, 9.75, 5);
  const Vec3 to = (point - at).normalized();
  const Vec3 tangent(-to.y(), to.x(), 0.0);  // (0.86, -0.51, 0): into the wall, along the trunk
  ASSERT_GT(tangent.x(), 0.0);
  const KinematicState self{at, heading_of(tangent)};
  const double d = (point - at).norm();
  const std::vector<world::NearPoint> near{{.point = point, .distance = d}};
  const ObstacleSense field;  // the field senses nothing within warn_distance here
  const ConstraintInputs in{c, Role::kPursuer, 0.1, self, Vec3(20, 0, 5), 1.0, field, bounds, nullptr, near};
  Vec3 moving;
  const Heading h = constrained_heading(in, {0.0, 0.0}, &moving);
  const Vec3 end = advance(self, h, moving, c.speed, 0.1, bounds).position;
  EXPECT_GE((end - point).norm(), c.radius + kHoldMargin - 1e-12);
  EXPECT_LE(end.x(), bounds.hi.x());
  // Unclamped, the tangent would have kept the distance: only the clamp closed on the trunk.
  const Vec3 unheld = advance(self, h, direction(h), c.speed, 0.1, bounds).position;
  EXPECT_LT((unheld - point).norm(), c.radius + kHoldMargin);
}

TEST(Constraints, WithFacesTheGuardKeepsClearOfTheArenasFacesToo) {
  AgentConfig c = agent_preset("peg3d", Role::kEvader);
  c.guard.faces = false;
  const Box bounds = Box{Vec3::Zero(), Vec3(35, 35, 20)}.shrunk(c.radius);
  ObstacleSense field;  // no obstacle of the map near
  // 0.6 m from the wall y = 0, inside stop_distance, flying straight at it.
  const KinematicState self{Vec3(10, 0.6, 5), Heading{-kPi / 2, kPi / 2}};
  const Vec3 opponent(10, 20, 5);
  const ConstraintInputs in{c, Role::kEvader, 0.1, self, opponent, 1.1, field, bounds, nullptr};
  const Heading unguarded = constrained_heading(in, {0.0, 0.0});
  EXPECT_LT(direction(unguarded).y(), -0.99);  // faces off: into the wall
  c.guard.faces = true;
  const ObstacleSense face = face_obstacle(c.guard, c.radius, self.position, bounds);
  ASSERT_TRUE(face.found);
  EXPECT_NEAR(face.distance, 0.6, 1e-12);
  EXPECT_TRUE(face.point.isApprox(Vec3(10, 0, 5)));
  // Like an obstacle 0.6 m away: the agent turns away from the wall by a full step.
  const Heading guarded = constrained_heading(in, {0.0, 0.0});
  EXPECT_NEAR(std::abs(wrap_angle(guarded.alpha + kPi / 2)), kPi / 4, 1e-9);
  // In a corner, 0.6 m from two walls, the rounded corner is nearer than either wall: the guard pushes along
  // the diagonal. With warn 2 m: the rounding's centre is 1.4 m from the point along each axis.
  const Vec3 corner(0.6, 0.6, 5);
  const ObstacleSense diagonal = face_obstacle(c.guard, c.radius, corner, bounds);
  ASSERT_TRUE(diagonal.found);
  EXPECT_NEAR(diagonal.distance, 2.0 - std::sqrt(2.0) * 1.4, 1e-12);
  EXPECT_NEAR((corner - diagonal.point).normalized().dot(Vec3(1, 1, 0).normalized()), 1.0, 1e-12);
  // Beyond warn_distance from every face there is nothing to guard.
  EXPECT_FALSE(face_obstacle(c.guard, c.radius, Vec3(10, 10, 10), bounds).found);
}

TEST(Constraints, WithFacesTheMapsObstacleStillHasTheLastWord) {
  // 0.6 m from the wall y = 0 and 0.5 m from an obstacle along +x, both inside stop_distance: the face
  // forbids -y, the obstacle +x. Holding still and asking for no turn, the agent turns (a bounded step at a
  // time) until it approaches neither; the obstacle, guarded last, is never approached once turned.
  AgentConfig c = agent_preset("peg3d", Role::kEvader);
  c.guard.faces = true;
  const Box bounds = Box{Vec3::Zero(), Vec3(35, 35, 20)}.shrunk(c.radius);
  const ObstacleSense obstacle{0.5, Vec3(10.5, 0.6, 5), true};
  for (const double alpha : {0.0, -0.5, -1.0, -kPi / 2}) {
    KinematicState self{Vec3(10, 0.6, 5), Heading{alpha, kPi / 2}};
    Vec3 d;
    for (int step = 0; step < 4; ++step) {
      const ConstraintInputs in{c, Role::kEvader, 0.1, self, Vec3(20, 20, 5), 1.1, obstacle, bounds, nullptr};
      self.heading = constrained_heading(in, {0.0, 0.0}, &d);
    }
    EXPECT_LE(d.x(), 1e-9) << alpha;   // not towards the obstacle
    EXPECT_GE(d.y(), -1e-9) << alpha;  // nor into the wall
  }
}

}  // namespace
}  // namespace peg3d::game
