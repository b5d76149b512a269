#include "players/scripted_policies.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/apollonius.hpp"
#include "solids_probe.hpp"

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

// The area centroid of the polygon in which the plane n.x = c cuts the box: its corners are where the box's 12
// edges cross the plane, in order of angle about their mean.
Vec3 cross_section_centroid(const Box& box, const Vec3& n, double c) {
  std::vector<Vec3> corners;
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 0; i < 4; ++i) {
      Vec3 a = box.lo, b = box.lo;
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      a[u] = b[u] = (i & 1) ? box.hi[u] : box.lo[u];
      a[w] = b[w] = (i & 2) ? box.hi[w] : box.lo[w];
      b[axis] = box.hi[axis];
      const double da = n.dot(a) - c, db = n.dot(b) - c;
      if ((da < 0) != (db < 0)) corners.push_back(a + (da / (da - db)) * (b - a));
    }
  }
  Vec3 mean = Vec3::Zero();
  for (const Vec3& x : corners) mean += x / double(corners.size());
  const auto [u, w] = perpendicular_frame(n);
  std::sort(corners.begin(), corners.end(), [&](const Vec3& a, const Vec3& b) {
    return std::atan2((a - mean).dot(w), (a - mean).dot(u)) < std::atan2((b - mean).dot(w), (b - mean).dot(u));
  });
  Vec3 sum = Vec3::Zero();
  double area = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Vec3& a = corners[i];
    const Vec3& b = corners[(i + 1) % corners.size()];
    const double t = 0.5 * (a - mean).cross(b - mean).dot(n);
    sum += t * (mean + a + b) / 3.0;
    area += t;
  }
  return sum / area;
}

// A team of four whose other three stand far outside the arena (their bisectors with the evader miss it).
AgentView voronoi_view(const Vec3& p, const Vec3& e, std::vector<KinematicState>& team) {
  team = {{{-500, 17, 10}, {}}, {p, {0.3, 1.2}}, {{600, 17, 10}, {}}, {{17, 900, 10}, {}}};
  AgentView v = view_of(team[1], {e, {0.5, 1.4}}, 1.0, 1.3);
  v.team = team;
  v.rank = 1;
  return v;
}

// Where the view's evader will be kVoronoiLead later, in the arena: the point a VoronoiPursuer partitions about.
Vec3 led(const AgentView& v) {
  return v.arena.clamp(v.other.position + kVoronoiLead * v.other_speed * direction(v.other.heading));
}

TEST(ScriptedPolicies, VoronoiHeadsForTheCentroidOfItsFaceOfTheEvadersCell) {
  // With no other pursuer's bisector in the arena, the face is the whole cross-section of the arena by the
  // bisector plane of the pursuer and the evader ahead (kVoronoiLead): the pursuer heads for its centroid.
  std::mt19937_64 rng(52);
  std::uniform_real_distribution<double> x(1.0, 34.0), z(1.0, 19.0);
  VoronoiPursuer voronoi(3.0);
  int tried = 0;
  while (tried < 200) {
    const Vec3 p(x(rng), x(rng), z(rng)), e(x(rng), x(rng), z(rng));
    std::vector<KinematicState> team;
    AgentView v = voronoi_view(p, e, team);
    v.other.heading = {x(rng) / 34.0 * 2.0 * kPi - kPi, z(rng) / 20.0 * kPi};  // any heading
    const Vec3 ahead = led(v);
    if ((p - ahead).norm() < kVoronoiChase + 1.0) continue;
    const Vec3 n = (p - ahead).normalized();
    const Vec3 centroid = cross_section_centroid(v.arena, n, n.dot(0.5 * (p + ahead)));
    ++tried;
    EXPECT_LT((after(v, voronoi.act(v)) - (centroid - p).normalized()).norm(), 1e-9) << p.transpose() << " " << e.transpose();
  }
}

TEST(ScriptedPolicies, VoronoiChasesByProportionalNavigationWhenItHasNoFaceIsNearOrHasLostTheEvader) {
  VoronoiPursuer voronoi(3.0);
  ProportionalNavigation pn(3.0);
  auto same = [&](const AgentView& v) {
    const Steering a = voronoi.act(v), b = pn.act(v);
    return a.d_alpha == b.d_alpha && a.d_theta == b.d_theta;
  };
  std::vector<KinematicState> team;
  AgentView v = voronoi_view({4, 17.5, 10}, {17.5, 17.5, 10}, team);
  const Vec3 ahead = led(v);
  EXPECT_FALSE(same(v));  // it has a face
  team[3].position = ahead - Vec3(1, 0, 0);  // a teammate 1 m from the evader ahead, on the pursuer's side
  EXPECT_TRUE(same(v));  // it is nearer than the evader to every point of the face, which is empty
  v = voronoi_view(ahead - Vec3(kVoronoiChase - 0.01, 0, 0), {17.5, 17.5, 10}, team);
  EXPECT_TRUE(same(v));  // near: the chase
  v = voronoi_view(ahead - Vec3(kVoronoiChase + 0.01, 0, 0), {17.5, 17.5, 10}, team);
  EXPECT_FALSE(same(v));
  v = voronoi_view({4, 17.5, 10}, {17.5, 17.5, 10}, team);
  v.other_age = kVoronoiSightAge + 0.1;
  EXPECT_TRUE(same(v));  // an old sighting
  v.other_age = kVoronoiSightAge;
  EXPECT_FALSE(same(v));
  v.team = v.team.subspan(1, 1);
  v.rank = 0;
  EXPECT_TRUE(same(v));  // alone
}

TEST(ScriptedPolicies, VoronoiByInterceptionChasesTowardWhereTheCoursesMeet) {
  // Where a VoronoiPursuer chases (near the evader ahead, on a fresh sighting), kInterception heads for the
  // interception point of the evader's straight course when there is one, else navigates as kNavigation does; where
  // it does not chase (a face, far) the two play the same. Random places, headings and evader speeds (slower, equal
  // and faster than the pursuer's 1 m/s).
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  VoronoiPursuer navigation(3.0), interception(3.0, VoronoiWay::kStraight, VoronoiChase::kInterception);
  auto same = [](const Steering& a, const Steering& b) { return a.d_alpha == b.d_alpha && a.d_theta == b.d_theta; };
  int met_slower = 0, met_faster = 0, never = 0, far = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const Vec3 e(2.0 + 31.0 * u(rng), 2.0 + 31.0 * u(rng), 2.0 + 16.0 * u(rng));
    const double r = trial % 4 == 0 ? 20.0 * u(rng) : 0.2 + 0.95 * kVoronoiChase * u(rng);  // far, or near
    const Vec3 p = Box{{0.5, 0.5, 0.5}, {34.5, 34.5, 19.5}}.clamp(e + r * direction({2.0 * kPi * u(rng), kPi * u(rng)}));
    std::vector<KinematicState> team;
    AgentView v = voronoi_view(p, e, team);
    v.other.heading = {2.0 * kPi * u(rng) - kPi, kPi * u(rng)};
    v.self.heading = {2.0 * kPi * u(rng) - kPi, kPi * u(rng)};
    v.other_speed = std::array{0.8, 1.0, 1.3}[trial % 3];  // every speed both far and near (trial % 12)
    if ((led(v) - p).norm() >= kVoronoiChase) {
      ++far;
      EXPECT_TRUE(same(interception.act(v), navigation.act(v))) << trial;  // its face, as before
      continue;
    }
    const auto x = interception_point(p, e, direction(v.other.heading), v.other_speed / v.self_speed);
    if (x) {
      ++(v.other_speed < v.self_speed ? met_slower : met_faster);
      EXPECT_LT((after(v, interception.act(v)) - (v.arena.clamp(*x) - p).normalized()).norm(), 1e-9) << trial;
    } else {
      ++never;
      EXPECT_TRUE(same(interception.act(v), navigation.act(v))) << trial;
    }
    v.other_age = kVoronoiSightAge + 0.1;  // an old sighting: the chase by navigation
    EXPECT_TRUE(same(interception.act(v), navigation.act(v))) << trial;
  }
  EXPECT_GE(met_slower, 50);  // a slower evader's course always meets the pursuer's
  EXPECT_GE(met_faster, 50);
  EXPECT_GE(never, 30);
  EXPECT_GE(far, 50);
}

TEST(ScriptedPolicies, VoronoiRouteGoesRoundAWallThatBlocksItsWayToTheFace) {
  // The pursuer east of a wall, the evader west of it: the face's centroid lies west, behind the wall. Told to
  // route, the pursuer heads for its roadmap's waypoint towards the centroid; plain voronoi heads straight at the
  // centroid; with the opening on the straight way both head at it. Pursuer, evader and opening vary.
  std::mt19937_64 rng(55);
  std::uniform_real_distribution<double> y(2.0, 18.0), z(2.0, 6.0), east(14.0, 19.0), west(0.5, 3.0);
  const Box arena{{0, 0, 0}, {20, 20, 8}};
  int blocked = 0, straight = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p(east(rng), y(rng), z(rng)), e(west(rng), y(rng), z(rng));
    std::vector<KinematicState> team;
    AgentView v = voronoi_view(p, e, team);
    v.arena = arena;
    const Vec3 ahead = led(v);
    const Vec3 n = (p - ahead).normalized();
    const Vec3 centroid = cross_section_centroid(arena, n, n.dot(0.5 * (p + ahead)));
    if ((p - ahead).norm() < kVoronoiChase + 1.0 || centroid.x() > 8.5) continue;
    // The opening on the straight way to the centroid (where it crosses x = 10) or 8 m off it, inside the wall.
    const double cross = p.y() + (centroid.y() - p.y()) * (p.x() - 10.0) / (p.x() - centroid.x());
    const bool on_the_way = trial % 2 == 0;
    double hole = on_the_way ? cross : cross + (cross < 10.0 ? 8.0 : -8.0);
    if (hole < 2.0 || hole > 18.0) continue;
    const peg3d::testing::BoxesProbe probe = peg3d::testing::wall_with_hole(hole, 4.0);
    v.probe = &probe;
    const bool clear_way = passable(probe, p, centroid, kPassage);
    if (on_the_way && !clear_way) continue;  // the opening's edges graze the margin: not this case
    VoronoiPursuer plain(3.0), routed(3.0, VoronoiWay::kRoute);
    plain.begin_episode(v, false);
    routed.begin_episode(v, false);
    EXPECT_LT((after(v, plain.act(v)) - (centroid - p).normalized()).norm(), 1e-9);
    if (clear_way) {
      ++straight;
      EXPECT_LT((after(v, routed.act(v)) - (centroid - p).normalized()).norm(), 1e-9);
      continue;
    }
    ++blocked;
    Roadmap map;
    map.build(arena, probe);
    const auto way = map.waypoint(probe, p, centroid, kPassage);
    ASSERT_TRUE(way.has_value());
    EXPECT_GT((*way - centroid).norm(), 1.0);
    EXPECT_LT((after(v, routed.act(v)) - (*way - p).normalized()).norm(), 1e-9) << p.transpose() << " " << e.transpose();
  }
  EXPECT_GE(blocked, 10);
  EXPECT_GE(straight, 5);
}

TEST(ScriptedPolicies, VoronoiGeodesicGoesForTheOpeningWhenTheEvadersCellIsOnlyReachedThroughIt) {
  // A team of four, the pursuer east of a wall and the evader west of it, the wall's only opening placed at random:
  // straight, the pursuer's face of the evader's cell lies behind the wall; by the ways round, the pursuer's border
  // with that cell (or the evader it chases) is reached only through the opening, so it heads for the opening in
  // plan.
  std::mt19937_64 rng(58);
  std::uniform_real_distribution<double> y(1.0, 19.0), z(1.0, 7.0), east(14.0, 19.0), west(1.0, 6.0), hole(3.0, 17.0);
  const Box arena{{0, 0, 0}, {20, 20, 8}};
  double least = 1.0;
  for (int trial = 0; trial < 100; ++trial) {
    const double h = hole(rng);
    const peg3d::testing::BoxesProbe probe = peg3d::testing::wall_with_hole(h, 2.0);
    const Vec3 p(east(rng), y(rng), z(rng)), e(west(rng), y(rng), z(rng));
    std::vector<KinematicState> team = {{{west(rng), y(rng), z(rng)}, {}}, {p, {0.3, 1.2}}, {{west(rng), y(rng), z(rng)}, {}},
                                        {{east(rng), y(rng), z(rng)}, {}}};
    // Equal speeds: against a faster evader, a pursuer with no face takes its Apollonius cell's border instead,
    // which can lie on the pursuer's side of the wall (the next test).
    AgentView v = view_of(team[1], {e, {0.5, 1.4}}, 1.0, 1.0);
    v.arena = arena;
    v.team = team;
    v.rank = 1;
    v.probe = &probe;
    VoronoiPursuer geodesic(3.0, VoronoiWay::kGeodesic);
    geodesic.begin_episode(v, false);
    // In plan: the way round is about where, not at what height (its goal is at the evader's height).
    const Vec3 opening(10.0, h, p.z()), heading = after(v, geodesic.act(v));
    const double towards = Vec3(heading.x(), heading.y(), 0.0).normalized().dot((opening - p).normalized());
    least = std::min(least, towards);
    EXPECT_GT(towards, 0.7) << "opening at y = " << h << ", pursuer " << p.transpose() << ", evader " << e.transpose();
  }
  EXPECT_LT(least, 0.99);  // not every way is straight at the opening's centre: the test asks the direction, not a point
}

TEST(ScriptedPolicies, VoronoiGeodesicCutsAFasterEvaderOffAheadWhereItWouldChaseItsTail) {
  // open_wall's wall, the evader running north up the east side into the corner past it, two pursuers on its heels
  // and two farther back (a lap seen in self-play, where the evader went round and round the wall with the team
  // behind it). The pursuer at the back shares no face with the evader's cell: against an evader as fast as itself
  // it chases it by proportional navigation; against one 1.3 times as fast it heads for its border with the cells
  // that evader reaches first, ahead of the evader by the wall's north end, where the evader's way round goes.
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5), turn(0.0, 0.6);
  const Box arena{{0, 0, 0}, {20, 20, 8}};
  peg3d::testing::BoxesProbe probe;
  probe.solids = {Box{{9.5, 3, -1}, {10.5, 17, 9}}};
  const Vec3 end(10.0, 17.0, 0.0);  // the wall's north end, in plan
  auto near = [&](double x, double y, double z) { return Vec3(x + jitter(rng), y + jitter(rng), z + jitter(rng)); };
  auto plan = [](Vec3 x) { return Vec3(x.x(), x.y(), 0.0); };
  int cut = 0, none = 0, ahead = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<KinematicState> team = {{near(12.8, 11.2, 5.5), {1.6, 1.57}}, {near(16.6, 14.3, 5.0), {1.2, 1.57}},
                                        {near(18.6, 12.7, 5.0), {1.5, 1.57}}, {near(14.6, 6.7, 5.0), {1.3, 1.57}}};
    const KinematicState evader{near(19.0, 16.8, 4.9), {kPi / 2 + turn(rng), kPi / 2}};
    AgentView v = view_of(team[0], evader, 1.0, 1.0);
    v.arena = arena;
    v.team = team;
    v.rank = 0;
    v.probe = &probe;
    Roadmap map;
    map.build(arena, probe);
    std::vector<Vec3> sources = {led(v)};
    for (const KinematicState& q : team) sources.push_back(q.position);
    map.partition(sources);
    if (map.border_point(1)) continue;  // it has a face: not this case
    ++cut;
    VoronoiPursuer same(3.0, VoronoiWay::kGeodesic), slower(3.0, VoronoiWay::kGeodesic);
    ProportionalNavigation pn(3.0);
    same.begin_episode(v, false);
    const Steering chase = same.act(v), expected = pn.act(v);
    EXPECT_EQ(chase.d_alpha, expected.d_alpha) << trial;
    EXPECT_EQ(chase.d_theta, expected.d_theta) << trial;
    v.other_speed = 1.3;
    sources[0] = led(v);  // farther ahead
    map.partition(sources);
    if (map.border_point(1)) {
      ++none;  // a face with this evader's cell
      continue;
    }
    map.partition(sources, 1.3);
    auto border = map.border_point(1);
    if (!border) {
      ++none;  // no face with that cell either: the chase
      continue;
    }
    ++ahead;
    // Ahead: nearer the wall's end than the evader is.
    EXPECT_LT((plan(*border) - end).norm(), (plan(sources[0]) - end).norm()) << trial << ": " << border->transpose();
    border->z() = sources[0].z();
    const Vec3& p = v.self.position;
    const Vec3 to = passable(probe, p, *border, kPassage) ? *border : *map.waypoint(probe, p, *border, kPassage);
    slower.begin_episode(v, false);
    EXPECT_LT((after(v, slower.act(v)) - (to - p).normalized()).norm(), 1e-9) << trial;
  }
  EXPECT_GE(cut, 20);
  EXPECT_GE(ahead, 15);
}

TEST(ScriptedPolicies, VoronoiGeodesicHeadsForItsBorderPointAtTheEvadersHeight) {
  // No solids, a team of four at random in the arena: a pursuer farther than kVoronoiGeodesicChase from the evader
  // ahead heads for the point of its border with the evader's cell nearest the border's centroid, moved to the
  // evader's height (ahead, kVoronoiLead).
  std::mt19937_64 rng(59);
  std::uniform_real_distribution<double> x(0.5, 19.5), z(0.5, 7.5);
  const Box arena{{0, 0, 0}, {20, 20, 8}};
  const peg3d::testing::BoxesProbe open;
  int headed = 0, moved = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<KinematicState> team;
    for (int k = 0; k < 4; ++k) team.push_back({{x(rng), x(rng), z(rng)}, {0.3, 1.2}});
    AgentView v = view_of(team[1], {{x(rng), x(rng), z(rng)}, {x(rng) / 10.0 - 1.0, z(rng) / 8.0 * kPi}}, 1.0, 1.3);
    v.arena = arena;
    v.team = team;
    v.rank = 1;
    v.probe = &open;
    const Vec3 ahead = led(v);
    if ((ahead - v.self.position).norm() < kVoronoiGeodesicChase + 0.5) continue;
    Roadmap map;
    map.build(arena, open);
    std::vector<Vec3> sources = {ahead};
    for (const KinematicState& q : team) sources.push_back(q.position);
    map.partition(sources);
    auto border = map.border_point(2);
    if (!border) continue;  // no border: the chase, tested for voronoi
    moved += std::abs(border->z() - ahead.z()) > 1.0;
    border->z() = ahead.z();
    VoronoiPursuer geodesic(3.0, VoronoiWay::kGeodesic);
    geodesic.begin_episode(v, false);
    EXPECT_LT((after(v, geodesic.act(v)) - (*border - v.self.position).normalized()).norm(), 1e-9) << trial;
    ++headed;
  }
  EXPECT_GE(headed, 50);
  EXPECT_GE(moved, 10);  // the height is not the border point's own in many trials
}

TEST(ScriptedPolicies, VoronoiRouteWithoutAProbePlaysAsVoronoi) {
  std::mt19937_64 rng(57);
  std::uniform_real_distribution<double> x(1.0, 34.0), z(1.0, 19.0);
  VoronoiPursuer plain(3.0), routed(3.0, VoronoiWay::kRoute), geodesic(3.0, VoronoiWay::kGeodesic);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<KinematicState> team;
    AgentView v = voronoi_view({x(rng), x(rng), z(rng)}, {x(rng), x(rng), z(rng)}, team);
    plain.begin_episode(v, false);
    routed.begin_episode(v, false);
    geodesic.begin_episode(v, false);
    const Steering a = plain.act(v), b = routed.act(v), c = geodesic.act(v);
    EXPECT_EQ(a.d_alpha, b.d_alpha);
    EXPECT_EQ(a.d_theta, b.d_theta);
    EXPECT_EQ(a.d_alpha, c.d_alpha);
    EXPECT_EQ(a.d_theta, c.d_theta);
  }
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
