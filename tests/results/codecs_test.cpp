// The JSON codecs of what runs produce (results/codecs.hpp): episodes, traces, agent summaries and trained
// models read back to the bit through the text a journal line holds.
#include "results/codecs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/error.hpp"
#include "game/game_config.hpp"
#include "players/lineup.hpp"
#include "players/policy_io.hpp"
#include "support/numbers.hpp"

namespace peg3d::results {
namespace {

using testing::kInf;
using testing::kNaN;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

game::EpisodeResult odd_episode() {
  game::EpisodeResult e;
  e.outcome = game::Outcome::kPursuerCollision;
  e.steps = 417;
  e.duration = 20.85;
  e.final_distance = 0.1 + 0.2;
  e.pursuer_path = -0.0;
  e.evader_path = 1e-300;
  e.collisions = 2;
  game::CollisionEvent c;
  c.step = 12;
  c.time = 0.6;
  c.agent = 1;
  c.role = game::Role::kEvader;
  c.kind = world::ObstacleKind::kMesh;
  c.obstacle_id = 3;
  c.triangle = 77;
  c.point = {1.0 / 3.0, 2.0, -5.5};
  c.normal = {0.0, 0.6, 0.8};
  c.fraction = 0.25;
  c.penetration = 1e-9;
  e.first_collision = c;
  e.pursuer_return = kInf;
  e.evader_return = -kInf;
  e.pursuer_pinned_steps = 3;
  e.evader_pinned_steps = 4;
  e.pursuer_agent_steps = 834;
  e.evader_agent_steps = 417;
  e.pursuers = 2;
  e.evaders = 1;
  e.captures = 0;
  e.capture_time_sum = kNaN;
  e.last_capture_time = 0.0;
  return e;
}

void expect_same(const game::EpisodeResult& a, const game::EpisodeResult& b) {
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_EQ(a.steps, b.steps);
  for (auto [x, y] : {std::pair{a.duration, b.duration}, {a.final_distance, b.final_distance}, {a.pursuer_path, b.pursuer_path},
                      {a.evader_path, b.evader_path}, {a.pursuer_return, b.pursuer_return}, {a.evader_return, b.evader_return},
                      {a.capture_time_sum, b.capture_time_sum}, {a.last_capture_time, b.last_capture_time}}) {
    EXPECT_TRUE(same_bits(x, y)) << x << " vs " << y;
  }
  EXPECT_EQ(a.collisions, b.collisions);
  EXPECT_EQ(a.pursuer_pinned_steps, b.pursuer_pinned_steps);
  EXPECT_EQ(a.evader_agent_steps, b.evader_agent_steps);
  EXPECT_EQ(a.pursuers, b.pursuers);
  ASSERT_EQ(a.first_collision.has_value(), b.first_collision.has_value());
  if (a.first_collision) {
    EXPECT_EQ(a.first_collision->kind, b.first_collision->kind);
    EXPECT_EQ(a.first_collision->triangle, b.first_collision->triangle);
    EXPECT_TRUE(same_bits(a.first_collision->point.x(), b.first_collision->point.x()));
    EXPECT_TRUE(same_bits(a.first_collision->penetration, b.first_collision->penetration));
  }
}

TEST(ResultsCodecs, EpisodesRoundTripToTheBitThroughText) {
  const game::EpisodeResult e = odd_episode();
  // Through the text, as a journal line goes.
  const nlohmann::json back = nlohmann::json::parse(episode_to_json(e).dump());
  expect_same(episode_from_json(back), e);
  game::EpisodeResult plain;
  expect_same(episode_from_json(nlohmann::json::parse(episode_to_json(plain).dump())), plain);
  EXPECT_TRUE(std::signbit(number_from_json(number_to_json(-kNaN))));
  EXPECT_THROW(episode_from_json(nlohmann::json::array({1, 2})), std::invalid_argument);
  EXPECT_THROW(number_from_json("zero"), std::invalid_argument);
}

TEST(ResultsCodecs, TracesSummariesAndModelsRoundTrip) {
  game::Trace t;
  t.agents = 2;
  t.roles = {game::Role::kPursuer, game::Role::kEvader};
  for (int k = 0; k < 3; ++k) {
    t.times.push_back(0.05 * k);
    for (int i = 0; i < 2; ++i) {
      game::AgentFrame f;
      f.state.position = {k + 0.1, i - 0.3, 1.0 / 7.0};
      f.state.heading = {0.5 * k, 1.2};
      f.percept.target_distance = 12.5 - k;
      f.percept.target = {0.1, -0.2};
      f.percept.obstacle = {3.25, {1, 2, 3}, k == 1};
      f.percept.to_obstacle = {kNaN, 0.0};
      f.percept.pinned = i == 1;
      f.command = {0.01, -0.02};
      f.reward = -kInf;
      f.active = k < 2;
      if (i == 0) f.opponent = 1, f.sees = k == 0, f.estimate = {k - 0.5, 2.0 / 3.0, 4.0};  // a pursuer with limited sight
      t.frames.push_back(f);
    }
  }
  t.captures.push_back({2, 0.1, 0, 1, 0.49});
  const game::Trace r = trace_from_json(nlohmann::json::parse(trace_to_json(t).dump()));
  ASSERT_EQ(r.agents, 2);
  ASSERT_EQ(r.frames.size(), t.frames.size());
  EXPECT_EQ(r.roles, t.roles);
  EXPECT_EQ(r.times, t.times);
  for (std::size_t n = 0; n < t.frames.size(); ++n) {
    const auto &a = t.frames[n], &b = r.frames[n];
    EXPECT_EQ(a.state.position, b.state.position);
    EXPECT_EQ(a.state.heading.alpha, b.state.heading.alpha);
    EXPECT_EQ(a.percept.obstacle.found, b.percept.obstacle.found);
    EXPECT_EQ(a.percept.obstacle.point, b.percept.obstacle.point);
    EXPECT_TRUE(std::isnan(b.percept.to_obstacle.azimuth));
    EXPECT_EQ(a.percept.pinned, b.percept.pinned);
    EXPECT_EQ(a.command.d_theta, b.command.d_theta);
    EXPECT_EQ(a.reward, b.reward);
    EXPECT_EQ(a.active, b.active);
    EXPECT_EQ(a.opponent, b.opponent);
    EXPECT_EQ(a.sees, b.sees);
    EXPECT_EQ(a.estimate, b.estimate);
  }
  ASSERT_EQ(r.captures.size(), 1u);
  EXPECT_EQ(r.captures[0].distance, 0.49);

  game::AgentSummary s{game::Role::kEvader, 1, 33.5, -2.25, 400, 0.125, 1, 0, -1.0};
  const game::AgentSummary s2 = agent_summary_from_json(nlohmann::json::parse(agent_summary_to_json(s).dump()));
  EXPECT_EQ(s2.role, s.role);
  EXPECT_EQ(s2.path, s.path);
  EXPECT_EQ(s2.captured_at, s.captured_at);

  players::Lineup lineup;
  players::RoleModels models;
  players::add_configured(lineup, game::preset("peg3d"), game::Role::kPursuer, 1, 5, &models);
  ASSERT_FALSE(models.empty());
  const players::RoleModels back =
      role_models_from_json(nlohmann::json::parse(role_models_to_json(models).dump()), game::Role::kPursuer);
  ASSERT_EQ(back.models.size(), models.models.size());
  EXPECT_EQ(back.of_agent, models.of_agent);
  EXPECT_EQ(players::policy_to_json(*back.models[0]), players::policy_to_json(*models.models[0]));
  EXPECT_THROW(role_models_from_json(role_models_to_json(models), game::Role::kEvader), InputError);
}

}  // namespace
}  // namespace peg3d::results
