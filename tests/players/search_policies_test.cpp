// The partial game's classic players (players/search_policies.hpp): with full information they play as pure pursuit
// and flee do; out of sight the searcher flies to the estimate and then visits every point of its lattice, the
// nearest first; in the pillar room the hider gets out of the pursuer's sight where flee stays in it.
#include "players/search_policies.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "core/random.hpp"
#include "game/episode.hpp"
#include "game/test_arena.hpp"
#include "players/registry.hpp"

namespace peg3d::players {
namespace {

using namespace peg3d::game;

AgentView random_arena_view(Rng& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  AgentView v;
  v.arena = {{0, 0, 0}, {35, 35, 20}};
  v.self = {{35 * u(rng), 35 * u(rng), 20 * u(rng)}, {kPi * (2 * u(rng) - 1), kPi * u(rng)}};
  v.other = {{35 * u(rng), 35 * u(rng), 20 * u(rng)}, {kPi * (2 * u(rng) - 1), kPi * u(rng)}};
  v.self_speed = 1.1, v.other_speed = 1.0, v.dt = 0.1;
  v.percept.obstacle = {5 * u(rng), {35 * u(rng), 35 * u(rng), 20 * u(rng)}, true};
  return v;
}

TEST(GameSearchPolicies, WithFullInformationTheyPlayAsPurePursuitAndFlee) {
  Rng rng(4);
  SearchPursuer search;
  HideEvader hide;
  PurePursuit pure;
  FleeLineOfSight flee;
  for (int k = 0; k < 500; ++k) {
    AgentView v = random_arena_view(rng);
    if (k == 0) search.begin_episode(v, false), hide.begin_episode(v, false);
    v.time = 0.1 * k;
    const Steering a = search.act(v), b = pure.act(v), c = hide.act(v), d = flee.act(v);
    EXPECT_EQ(a.d_alpha, b.d_alpha);
    EXPECT_EQ(a.d_theta, b.d_theta);
    EXPECT_EQ(c.d_alpha, d.d_alpha);
    EXPECT_EQ(c.d_theta, d.d_theta);
  }
}

// Step k of the agent of `v` with no world around it and its opponent out of sight since the start: it turns as
// `policy` asks (no bound) and flies at its speed, kept in the arena.
void fly(AgentView& v, Policy& policy, int k) {
  v.time = k * v.dt;
  v.other_age = v.time;
  const Steering u = policy.act(v);
  v.self.heading = steer(v.self.heading, u, kPi);
  v.self.position = v.arena.clamp(v.self.position + v.self_speed * v.dt * direction(v.self.heading));
}

TEST(GameSearchPolicies, OutOfSightTheSearcherGoesToTheEstimateThenVisitsEveryLatticePoint) {
  // No world: the agent turns as it is told and flies 1.1 m/s; the evader, never seen again, was last at `last`.
  for (const Vec3& last : {Vec3(30, 5, 3), Vec3(12, 28, 15)}) {
    AgentView v;
    v.arena = {{0, 0, 0}, {35, 35, 20}};
    v.self = {{3, 3, 3}, {0.3, 1.2}};
    v.other = {last, {}};
    v.other_visible = false;
    v.self_speed = 1.1, v.dt = 0.1;
    SearchPursuer s;
    s.begin_episode(v, false);
    // The lattice: 7 x 7 x 4 points, 5 m apart.
    std::set<std::array<int, 3>> visited;
    double arrived = -1.0, first_point = -1.0;
    Vec3 first_at = Vec3::Zero();
    for (int k = 0; k < 40000 && visited.size() < 196; ++k) {
      fly(v, s, k);
      if (arrived < 0 && (v.self.position - last).norm() <= SearchPursuer::kArrive) arrived = v.time;
      for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 7; ++j)
          for (int h = 0; h < 4; ++h) {
            const Vec3 w(2.5 + 5 * i, 2.5 + 5 * j, 2.5 + 5 * h);
            if ((w - v.self.position).norm() <= SearchPursuer::kVisit && arrived >= 0 && v.time > arrived) {
              if (visited.empty()) first_point = v.time, first_at = w;
              visited.insert({i, j, h});
            }
          }
    }
    EXPECT_GT(arrived, 0.0);
    EXPECT_NEAR(arrived, ((last - Vec3(3, 3, 3)).norm() - SearchPursuer::kArrive) / 1.1, 3.0);  // straight there
    EXPECT_EQ(visited.size(), 196u);  // one round visits every point
    EXPECT_LT((first_at - last).norm(), 5.0);  // and starts beside the last sighting
    EXPECT_GT(first_point, arrived);
  }
}

TEST(GameSearchPolicies, WithAMapTheSearcherVisitsTheUnknownSpaceFirst) {
  // Its map has seen the arena's west (x < 15); the evader was last seen in the west, at (5, 5, 3). Without
  // the map the search begins among the points beside the last sighting, and 25 s on it is still in the west; with
  // it, it heads for the unknown east at once.
  struct WestKnown final : SightProbe {
    bool clear(const Vec3&, const Vec3&) const override { return true; }
    bool mapped(const Vec3& p) const override { return p.x() < 15.0; }
  } west;
  struct NoMap final : SightProbe {
    bool clear(const Vec3&, const Vec3&) const override { return true; }
  } none;
  for (const SightProbe* probe : {static_cast<const SightProbe*>(&none), static_cast<const SightProbe*>(&west)}) {
    AgentView v;
    v.arena = {{0, 0, 0}, {35, 35, 20}};
    v.self = {{4, 4, 3}, {0.3, 1.2}};
    v.other = {{5, 5, 3}, {}};
    v.other_visible = false;
    v.self_speed = 1.1, v.dt = 0.1;
    v.probe = probe;
    SearchPursuer s;
    s.begin_episode(v, false);
    for (int k = 0; k <= 250; ++k) fly(v, s, k);
    if (probe == &west) {
      EXPECT_GT(v.self.position.x(), 15.0) << "the unknown east first";
    } else {
      EXPECT_LT(v.self.position.x(), 15.0) << "beside the last sighting first";
    }
  }
}

// The hider or flee against a pursuer flying along y = 5 past the pillar room's pillar; the share of steps in which
// the pursuer saw the evader.
double seen_share(const std::string& evader) {
  GameConfig c = preset("peg3d");
  c.initial_heading = InitialHeading::kPlusX;
  c.pursuer.motion_space = false;
  c.pursuer.speed = 0.5;
  for (AgentConfig* a : {&c.pursuer, &c.evader}) a->sensors.sight.enabled = true;
  c.evader = scripted_agent(c.evader, evader);
  const Sim sim(testing::pillar_room(), c);
  SimState st(sim);
  reset(sim, st, testing::scenario("s", {3, 5, 5}, {15, 10, 5}), 1);
  auto e = make_player(c.evader, Role::kEvader, 1);
  e->begin_episode(observe(st, 1), false);
  int seen = 0, steps = 0;
  std::vector<Steering> u(2);
  while (!st.done && st.time < 40.0) {
    u[1] = e->act(observe(st, 1));
    step(sim, st, u);
    seen += observe(st, 0).other_visible, ++steps;
  }
  return double(seen) / steps;
}

TEST(GameSearchPolicies, TheHiderGetsOutOfSightBehindThePillarWhereFleeStaysInIt) {
  const double hide = seen_share("hide"), flee = seen_share("flee");
  EXPECT_LT(hide, 0.3) << "flee " << flee;  // 0.185 on 2026-12-04
  EXPECT_GT(flee, 0.8) << "hide " << hide;
}

}  // namespace
}  // namespace peg3d::players
