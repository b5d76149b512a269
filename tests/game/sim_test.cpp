// The steppable game: reset/step/observe, external commands, teams (captures, opponents, rewards, agent
// collisions) and the start checks.
#include "game/sim.hpp"

#include <filesystem>
#include <limits>
#include <fstream>
#include <random>
#include <regex>

#include <gtest/gtest.h>

#include "game/episode.hpp"
#include "players/scripted_policies.hpp"
#include "game/views.hpp"
#include "test_arena.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"
#include "world/bodies/mover_timeline.hpp"

namespace peg3d::game {
namespace {

using namespace peg3d::players;

using testing::make_arena;
using testing::scenario;
using testing::team;

const Vec3 kSize(35, 35, 20);

GameConfig stationary_evaders(const std::string& pursuer = "pure-pursuit") {
  GameConfig c = preset("peg3d");
  c.pursuer.policy = pursuer;
  c.evader.policy = "flee";
  c.evader.speed = 0.0;
  return c;
}

TEST(Sim, ExternalCommandsReproduceThePolicysEpisode) {
  // Record pure pursuit against flee, then drive the pursuer from the recorded commands through step():
  // every instant and every reward is the same, bit for bit.
  const auto s = scenario("chase", {5, 5, 5}, {20, 25, 12});
  GameConfig c = preset("peg3d");
  c.pursuer.policy = "pure-pursuit";
  c.evader.policy = "flee";
  const Sim sim(make_arena(kSize, {{{12, 15, 8}, 1.5}}, {s}), c);
  Trace recorded;
  const EpisodeResult original = testing::play_once(sim, s, 7, &recorded);
  ASSERT_GT(recorded.frame_count(), 50);

  SimState state(sim);
  reset(sim, state, s, 7);
  FleeLineOfSight flee;
  std::vector<Steering> commands(2);
  int k = 0;
  while (!state.done) {
    ++k;
    commands[0] = recorded.at(k, 0).command;
    commands[1] = flee.act(observe(state, 1));
    const StepEvents& ev = step(sim, state, commands);
    for (int i = 0; i < 2; ++i) {
      ASSERT_EQ(state.agents[std::size_t(i)].kinematics.position, recorded.at(k, i).state.position) << "step " << k;
      ASSERT_EQ(ev.agents[std::size_t(i)].reward.total, recorded.at(k, i).reward) << "step " << k;
    }
  }
  const EpisodeResult replayed = summarize(state);
  EXPECT_EQ(k, recorded.frame_count() - 1);
  EXPECT_EQ(replayed.outcome, original.outcome);
  EXPECT_EQ(replayed.pursuer_return, original.pursuer_return);
  EXPECT_EQ(replayed.evader_path, original.evader_path);

  // The same commands as a policy inside play(): the same episode again.
  std::vector<Steering> script;
  for (int f = 1; f < recorded.frame_count(); ++f) script.push_back(recorded.at(f, 0).command);
  CommandScript pursuer(script);
  FleeLineOfSight evader;
  Policy* policies[] = {&pursuer, &evader};
  SimState again(sim);
  const EpisodeResult scripted = play(sim, again, s, policies, false, 7);
  EXPECT_EQ(scripted.steps, original.steps);
  EXPECT_EQ(scripted.pursuer_return, original.pursuer_return);
  EXPECT_EQ(scripted.final_distance, original.final_distance);
}

// Everything a step can change, as bits: two states that agree here step on alike.
std::vector<double> snapshot(const SimState& st) {
  std::vector<double> x{st.time, double(st.step), double(st.free_evaders), double(st.done), double(st.collisions)};
  for (const AgentState& a : st.agents) {
    const KinematicState& k = a.kinematics;
    x.insert(x.end(), {k.position.x(), k.position.y(), k.position.z(), k.heading.alpha, k.heading.theta, a.path,
                       a.total_reward, double(a.steps), double(a.active), double(a.opponent),
                       a.view.percept.target_distance});
  }
  return x;
}

// A command that is not finite, for an agent in the game, is refused at step()'s entry in every build (this
// suite runs in Release): CommandError names the step and the agent, and nothing is stepped. The state then
// steps on exactly as one that was never given the bad command.
TEST(Sim, StepRefusesANonFiniteCommandNamingTheStepAndTheAgent) {
  const auto s = team("2v1", {{5, 10, 10}, {5, 30, 10}}, {{20, 20, 10}});
  const Sim sim(make_arena(kSize, {}, {s}), stationary_evaders());
  SimState state(sim), twin(sim);
  reset(sim, state, s, 3);
  reset(sim, twin, s, 3);
  const std::vector<Steering> good{{0.05, -0.02}, {-0.1, 0.03}, {0.0, 0.0}};
  for (int k = 0; k < 5; ++k) step(sim, state, good), step(sim, twin, good);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const char* names[] = {"pursuer 0", "pursuer 1", "evader 0"};
  for (int i = 0; i < 3; ++i) {
    for (const double bad : {nan, inf, -inf}) {
      for (const int component : {0, 1}) {
        std::vector<Steering> commands = good;
        (component == 0 ? commands[std::size_t(i)].d_alpha : commands[std::size_t(i)].d_theta) = bad;
        const std::vector<double> before = snapshot(state);
        try {
          step(sim, state, commands);
          ADD_FAILURE() << "agent " << i << " given " << bad << " was stepped";
        } catch (const CommandError& e) {
          EXPECT_EQ(e.step(), 6);
          EXPECT_EQ(e.agent(), i);
          const std::string what = e.what();
          EXPECT_NE(what.find("step 6: agent " + std::to_string(i) + " (" + names[i] + "): steering command ("),
                    std::string::npos) << what;
          EXPECT_NE(what.find("not finite; nothing was stepped"), std::string::npos) << what;
        }
        EXPECT_EQ(snapshot(state), before);
      }
    }
  }
  for (int k = 0; k < 20; ++k) step(sim, state, good), step(sim, twin, good);
  EXPECT_EQ(snapshot(state), snapshot(twin));
}

TEST(Sim, StepRefusesACommandCountThatIsNotTheAgentCount) {
  const auto s = team("2v1", {{5, 10, 10}, {5, 30, 10}}, {{20, 20, 10}});
  const Sim sim(make_arena(kSize, {}, {s}), stationary_evaders());
  SimState state(sim);
  reset(sim, state, s, 3);
  for (const std::size_t n : {0u, 2u, 4u}) {
    const std::vector<Steering> commands(n);
    try {
      step(sim, state, commands);
      ADD_FAILURE() << n << " commands were stepped";
    } catch (const CommandError& e) {
      EXPECT_EQ(e.agent(), -1);
      EXPECT_EQ(std::string(e.what()), "step 1: " + std::to_string(n) + " steering commands for 3 agents; nothing was stepped");
    }
    EXPECT_EQ(state.step, 0);
  }
}

// An agent out of the game (a captured evader) takes no command: whatever its entry holds is ignored.
TEST(Sim, TheCommandsOfAgentsOutOfTheGameAreIgnoredEvenWhenNotFinite) {
  // As in EveryEvaderCanBeCapturedByAnyPursuerAndLeavesTheGame: P0 captures E0 (agent 2) at step 82.
  const auto s = team("2v2", {{5, 10, 10}, {5, 30, 10}}, {{15, 10, 10}, {25, 30, 10}});
  const Sim sim(make_arena(kSize, {}, {s}), stationary_evaders());
  SimState state(sim);
  reset(sim, state, s, 1);
  PurePursuit chase;
  std::vector<Steering> commands(4);
  while (state.agents[2].active) {
    for (int i = 0; i < 2; ++i) commands[std::size_t(i)] = chase.act(observe(state, i));
    step(sim, state, commands);
  }
  EXPECT_EQ(state.step, 82);
  commands[2] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()};
  for (int i = 0; i < 2; ++i) commands[std::size_t(i)] = chase.act(observe(state, i));
  step(sim, state, commands);
  EXPECT_EQ(state.step, 83);
}

// A policy whose output is not finite (a network that overflowed) ends play() with the step's CommandError.
TEST(Sim, APolicyThatEmitsNaNEndsTheEpisodeWithACommandError) {
  struct Overflowing final : Policy {
    int calls = 0;
    Steering act(const AgentView&) override {
      return {++calls < 12 ? 0.0 : std::numeric_limits<double>::quiet_NaN(), 0.0};
    }
  };
  const auto s = scenario("chase", {5, 5, 5}, {20, 25, 12});
  const Sim sim(make_arena(kSize, {}, {s}), stationary_evaders());
  SimState state(sim);
  Overflowing bad;
  FleeLineOfSight flee;
  Policy* policies[] = {&bad, &flee};
  try {
    play(sim, state, s, policies, false, 5);
    ADD_FAILURE() << "the episode ended normally";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.step(), 12);
    EXPECT_EQ(e.agent(), 0);
  }
}

TEST(Sim, ResetIsAFunctionOfTheScenarioAndTheSeedOnly) {
  const auto s = scenario("open", {5, 5, 3}, {20, 25, 8});
  GameConfig c = preset("peg3d");
  c.initial_heading = InitialHeading::kRandom;
  const Sim sim(make_arena(kSize, {}, {s}), c);
  SimState a(sim), b(sim);
  reset(sim, a, s, 42);
  // b first plays a while, then is reset: no trace of its past remains.
  reset(sim, b, s, 1);
  std::vector<Steering> commands(2, Steering{0.3, -0.2});
  for (int k = 0; k < 30; ++k) step(sim, b, commands);
  reset(sim, b, s, 42);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(a.agents[std::size_t(i)].kinematics.position, b.agents[std::size_t(i)].kinematics.position);
    EXPECT_EQ(a.agents[std::size_t(i)].kinematics.heading.alpha, b.agents[std::size_t(i)].kinematics.heading.alpha);
    EXPECT_EQ(a.agents[std::size_t(i)].kinematics.heading.theta, b.agents[std::size_t(i)].kinematics.heading.theta);
    EXPECT_EQ(b.agents[std::size_t(i)].path, 0.0);
  }
  EXPECT_EQ(b.step, 0);
  EXPECT_FALSE(b.done);
  reset(sim, b, s, 43);
  EXPECT_NE(a.agents[0].kinematics.heading.alpha, b.agents[0].kinematics.heading.alpha);
}

TEST(Sim, EveryEvaderCanBeCapturedByAnyPursuerAndLeavesTheGame) {
  // P0 is 10 m from E0, P1 20 m from E1 (each nearer its own than the other's); the evaders stand still.
  // P0 captures E0 when 10 - 0.11 k <= 1, at k = 82; P1 captures E1 at k = ceil(19 / 0.11) = 173 (P0,
  // retargeted at E1 at 22.8 m, would need 198 more steps).
  const auto s = team("2v2", {{5, 10, 10}, {5, 30, 10}}, {{15, 10, 10}, {25, 30, 10}});
  const Sim sim(make_arena(kSize, {}, {s}), stationary_evaders());
  Trace trace;
  const EpisodeResult r = testing::play_once(sim, s, 1, &trace);
  EXPECT_EQ(r.outcome, Outcome::kCapture);
  EXPECT_EQ(r.evaders, 2);
  EXPECT_EQ(r.captures, 2);
  EXPECT_EQ(r.steps, 173);
  ASSERT_EQ(trace.captures.size(), 2u);
  EXPECT_EQ(trace.captures[0].step, 82);
  EXPECT_EQ(trace.captures[0].pursuer, 0);
  EXPECT_EQ(trace.captures[0].evader, 2);
  EXPECT_EQ(trace.captures[1].step, 173);
  EXPECT_EQ(trace.captures[1].pursuer, 1);
  EXPECT_EQ(trace.captures[1].evader, 3);
  EXPECT_NEAR(r.capture_time_sum, 8.2 + 17.3, 1e-9);
  EXPECT_NEAR(r.last_capture_time, 17.3, 1e-9);
  // The captured evader is out of the game from its capture on; P0 turned to the remaining evader.
  EXPECT_TRUE(trace.at(82, 2).active);
  EXPECT_FALSE(trace.at(83, 2).active);
  EXPECT_EQ(trace.at(83, 0).percept.target_distance, (trace.at(83, 3).state.position - trace.at(83, 0).state.position).norm());
  EXPECT_LT(trace.at(172, 0).percept.target_distance, trace.at(83, 0).percept.target_distance);
}

TEST(Sim, CaptureRewardGoesToTheCapturerAndTheCapturedOrToTheTeams) {
  const auto s = team("2v2", {{5, 10, 10}, {5, 30, 10}}, {{15, 10, 10}, {25, 30, 10}});
  for (const CaptureReward rule : {CaptureReward::kIndividual, CaptureReward::kTeam}) {
    GameConfig c = stationary_evaders();
    c.team.capture_reward = rule;
    const Sim sim(make_arena(kSize, {}, {s}), c);
    SimState state(sim);
    Lineup l = testing::lineup_for(c, s);
    reset(sim, state, s, 1);
    std::vector<Steering> commands(4);
    for (int k = 0; k < 82; ++k) {
      for (int i = 0; i < 4; ++i) commands[std::size_t(i)] = l[i].act(observe(state, i));
      step(sim, state, commands);
    }
    const StepEvents& ev = state.events;
    ASSERT_EQ(ev.captures.size(), 1u);
    const bool team_rule = rule == CaptureReward::kTeam;
    EXPECT_EQ(ev.agents[0].reward.success, 20.0);
    EXPECT_EQ(ev.agents[1].reward.success, team_rule ? 20.0 : 0.0);
    EXPECT_EQ(ev.agents[2].reward.success, -20.0);
    EXPECT_EQ(ev.agents[3].reward.success, team_rule ? -20.0 : 0.0);
    EXPECT_TRUE(ev.agents[2].terminal);   // the captured evader's game is over
    EXPECT_FALSE(ev.agents[0].terminal);  // the others play on
    EXPECT_FALSE(ev.terminal);
    EXPECT_FALSE(state.agents[2].active);
  }
}

TEST(Sim, OpponentsAreTheNearestOrTheAssignedOne) {
  // Both pursuers are nearest to E0; by assignment P1 plays E1.
  const auto s = team("2v2", {{5, 10, 10}, {5, 12, 10}}, {{10, 10, 10}, {30, 30, 10}});
  GameConfig c = preset("peg3d");
  const Sim nearest(make_arena(kSize, {}, {s}), c);
  SimState st(nearest);
  reset(nearest, st, s, 0);
  EXPECT_EQ(st.agents[0].opponent, 2);
  EXPECT_EQ(st.agents[1].opponent, 2);
  EXPECT_EQ(st.agents[2].opponent, 0);
  EXPECT_EQ(st.agents[3].opponent, 1);  // (30,30) is nearer to (5,12) than to (5,10)
  EXPECT_EQ(observe(st, 1).opponent, 2);
  c.team.pursuer_target = OpponentChoice::kAssigned;
  const Sim assigned(make_arena(kSize, {}, {s}), c);
  SimState st2(assigned);
  reset(assigned, st2, s, 0);
  EXPECT_EQ(st2.agents[0].opponent, 2);
  EXPECT_EQ(st2.agents[1].opponent, 3);
  EXPECT_EQ(observe(st2, 1).other.position, Vec3(30, 30, 10));
}

TEST(Sim, AViewsTeamIsItsRolesAgentsAsTheyAreNowInRankOrder) {
  const auto s = team("3v2", {{5, 10, 10}, {5, 20, 10}, {5, 30, 10}}, {{25, 10, 10}, {25, 30, 10}});
  const Sim sim(make_arena(kSize, {}, {s}), preset("peg3d"));
  SimState st(sim);
  reset(sim, st, s, 3);
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < st.agent_count(); ++i) {
      const AgentView& v = st.agents[std::size_t(i)].view;
      const int first = i < st.pursuers ? 0 : st.pursuers;
      ASSERT_EQ(int(v.team.size()), i < st.pursuers ? 3 : 2);
      EXPECT_EQ(v.rank, i - first);
      for (std::size_t m = 0; m < v.team.size(); ++m) {
        EXPECT_EQ(v.team[m].position, st.agents[std::size_t(first) + m].kinematics.position);
        EXPECT_EQ(v.team[m].heading.alpha, st.agents[std::size_t(first) + m].kinematics.heading.alpha);
      }
    }
    const std::vector<Steering> turn(st.agents.size(), Steering{0.2, -0.1});
    step(sim, st, turn);
  }
}

TEST(Sim, AgentsCollideWhenConfiguredAndPassThroughOtherwise) {
  // Capture only at 0.1 m, radii 0.25 m: a pursuer closing on a standing evader from 5 m touches it after
  // 4.5 m, at 4.5 / 1.1 s, when agents collide; otherwise it captures at 5 - 0.11 k <= 0.1, k = 45.
  const auto s = scenario("touch", {10, 17.5, 10}, {15, 17.5, 10});
  GameConfig c = stationary_evaders();
  c.capture_distance = 0.1;
  const Sim passing(make_arena(kSize, {}, {s}), c);
  const EpisodeResult free_run = testing::play_once(passing, s, 1);
  EXPECT_EQ(free_run.outcome, Outcome::kCapture);
  EXPECT_EQ(free_run.steps, 45);
  c.team.agent_collisions = AgentCollisions::kOpponents;
  const Sim colliding(make_arena(kSize, {}, {s}), c);
  Trace trace;
  const EpisodeResult r = testing::play_once(colliding, s, 1, &trace);
  EXPECT_EQ(r.outcome, Outcome::kPursuerCollision);
  ASSERT_TRUE(r.first_collision.has_value());
  EXPECT_EQ(r.first_collision->kind, world::ObstacleKind::kAgent);
  EXPECT_EQ(r.first_collision->agent, 0);
  EXPECT_EQ(r.first_collision->obstacle_id, 1);
  EXPECT_NEAR(r.first_collision->time, 4.5 / 1.1, 1e-9);
  EXPECT_NEAR(r.first_collision->point.x(), 14.75, 1e-9);
  ASSERT_EQ(trace.collisions.size(), 2u);  // both agents report the contact
  EXPECT_EQ(trace.collisions[1].agent, 1);
  EXPECT_EQ(trace.collisions[1].obstacle_id, 0);
  const double gap = (trace.at(r.steps, 1).state.position - trace.at(r.steps, 0).state.position).norm();
  EXPECT_GT(gap, 0.5);  // stopped a hair before touching
  EXPECT_LT(gap, 0.5 + 2e-3);
  // Teammates only: the pursuer and the evader pass through each other again.
  c.team.agent_collisions = AgentCollisions::kTeammates;
  const Sim teammates(make_arena(kSize, {}, {s}), c);
  EXPECT_EQ(testing::play_once(teammates, s, 1).outcome, Outcome::kCapture);
}

TEST(Sim, OverlappingTeammatesCannotStartWhenTeammatesCollide) {
  const auto s = team("crowded", {{5, 10, 10}, {5, 10.3, 10}}, {{30, 30, 10}});
  GameConfig c = preset("peg3d");
  EXPECT_NO_THROW(Sim(make_arena(kSize, {}, {s}), c));
  c.team.agent_collisions = AgentCollisions::kTeammates;
  EXPECT_THROW(Sim(make_arena(kSize, {}, {s}), c), StartError);
}

TEST(Sim, ScenariosNeedAPursuerAndAnEvader) {
  const auto ok = scenario("ok", {5, 5, 5}, {30, 30, 5});
  const Sim sim(make_arena(kSize, {}, {ok}), preset("peg3d"));
  SimState state(sim);
  world::Scenario lonely = ok;
  lonely.evaders.clear();
  EXPECT_THROW(reset(sim, state, lonely, 0), InvalidParameter);
  EXPECT_THROW(sim.check_scenario(lonely), InvalidParameter);
}

// Every file in tests/data/maps/bad-starts/ is a valid map whose start cannot be played with the default
// agents. Its first line says what the game must report: # expect: LINE FIELD MESSAGE-FRAGMENT
TEST(Sim, BadStartsNameTheMapFileLineAndField) {
  const auto dir = std::filesystem::path(PEG3D_TEST_DATA_DIR) / "maps" / "bad-starts";
  int cases = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    ++cases;
    std::ifstream in(entry.path());
    std::string first;
    std::getline(in, first);
    std::smatch m;
    ASSERT_TRUE(std::regex_match(first, m, std::regex(R"(# expect: (\d+) (\S+) (.+))"))) << entry.path();
    const auto arena = world::Arena::build(world::load_map(entry.path()));
    try {
      Sim sim(arena, preset("peg3d"));
      ADD_FAILURE() << "accepted " << entry.path();
    } catch (const StartError& e) {
      EXPECT_EQ(e.file(), entry.path());
      EXPECT_EQ(e.line(), std::stoi(m[1])) << e.what();
      EXPECT_EQ(e.field(), m[2].str()) << e.what();
      EXPECT_NE(std::string(e.what()).find(m[3].str()), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(entry.path().string() + ":" + m[1].str() + ": ", 0), 0u) << e.what();
    }
  }
  EXPECT_GE(cases, 3);
}

TEST(Sim, StartsAreKeptARadiusInsideTheArena) {
  const auto s = scenario("edge", {0.1, 5, 5}, {30, 30, 19.95});
  const Sim sim(make_arena(kSize, {}, {s}), preset("peg3d"));
  SimState st(sim);
  reset(sim, st, s, 0);
  EXPECT_EQ(st.agents[0].kinematics.position, Vec3(0.25, 5, 5));
  EXPECT_EQ(st.agents[1].kinematics.position, Vec3(30, 30, 19.75));
}

// A standing evader (speed 0) on a mover's line: the mover's ball of radius 1 comes along x at 5 m/s from
// x = 3 and touches the evader's 0.25 m sphere at x = 12 when its centre reaches 10.75, at t = 7.75 / 5 = 1.55 s.
std::shared_ptr<const world::Arena> crossing_arena(double evader_y) {
  world::MapSpec m;
  m.name = "crossing";
  m.bounds = {Vec3::Zero(), Vec3(35, 35, 20)};
  m.resolution = 0.25;
  m.floor_is_obstacle = m.ceiling_is_obstacle = m.walls_is_obstacle = false;
  world::MoverSpec mover;
  mover.shape = {Shape::Kind::kSphere, 1.0, 1.0, Vec3::Ones()};
  mover.motion = world::MoverSpec::Motion::kPath;
  mover.path = {{Vec3(3, 10, 10), Vec3(33, 10, 10)}, 5.0, false};
  m.movers.push_back(mover);
  m.scenarios.push_back(scenario("crossing", {12, 30, 10}, {12, evader_y, 10}));
  return world::Arena::build(m);
}

GameConfig standing_evader() {
  GameConfig c = preset("peg3d");
  c.pursuer.policy = "pure-pursuit";
  c.pursuer.speed = 0.01;  // far away and slow: the game lasts until the mover arrives
  c.evader.policy = "flee";
  c.evader.speed = 0.0;
  c.evader.guard.enabled = false;
  return c;
}

TEST(Sim, AnAgentInAMoversWayIsHitWhenTheMoverArrives) {
  const auto arena = crossing_arena(10.0);
  const Sim sim(arena, standing_evader());
  Trace trace;
  const EpisodeResult r = testing::play_once(sim, arena->map().scenarios[0], 1, &trace);
  EXPECT_EQ(r.outcome, Outcome::kEvaderCollision);
  ASSERT_TRUE(r.first_collision.has_value());
  EXPECT_EQ(r.first_collision->agent, 1);
  EXPECT_EQ(r.first_collision->kind, world::ObstacleKind::kMover);
  EXPECT_EQ(r.first_collision->obstacle_id, 0);
  EXPECT_NEAR(r.first_collision->time, 1.55, 1e-4);
  EXPECT_EQ(r.first_collision->step, 16);
  EXPECT_NEAR(r.first_collision->point.x(), 11.75, 1e-3);
}

TEST(Sim, AnAgentAHairOutsideTheMoversReachIsNotHit) {
  const auto arena = crossing_arena(10.0 + 1.25 + 1e-3);
  GameConfig c = standing_evader();
  c.time_limit = 8.0;  // the mover passes x = 12 at 1.8 s and leaves by 6 s
  const Sim sim(arena, c);
  const EpisodeResult r = testing::play_once(sim, arena->map().scenarios[0], 1);
  EXPECT_EQ(r.outcome, Outcome::kTimeout);
  EXPECT_EQ(r.collisions, 0);
}

// A ball orbiting a standing evader fast (a turn in 0.01 s, 785 m/s), its surface 1.5e-4 m from the evader's
// sphere: the contact search cannot finish within its bound (MoverTimeline::kMaxAdvancementSteps). It answers a
// contact, never none: a collision, counted in the step's events and the episode's result.
TEST(Sim, AContactSearchThatGivesUpIsACollisionCountedInTheStepsEvents) {
  world::MapSpec m;
  m.name = "orbit";
  m.bounds = {Vec3::Zero(), Vec3(35, 35, 20)};
  m.resolution = 0.25;
  m.floor_is_obstacle = m.ceiling_is_obstacle = m.walls_is_obstacle = false;
  const Vec3 evader(12, 12, 10);
  const GameConfig c = standing_evader();
  world::MoverSpec mover;
  mover.shape = {Shape::Kind::kSphere, 1.0, 1.0, Vec3::Ones()};
  mover.motion = world::MoverSpec::Motion::kOrbit;
  mover.orbit = {evader, 1.0 + c.evader.radius + 1.5e-4, 0.01, Vec3::UnitZ(), 0.0};
  m.movers.push_back(mover);
  m.scenarios.push_back(scenario("orbit", {30, 30, 10}, evader));
  const auto arena = world::Arena::build(m);
  const Sim sim(arena, c);
  SimState state(sim);
  reset(sim, state, arena->map().scenarios[0], 1);
  const std::vector<Steering> still(2);
  const StepEvents& ev = step(sim, state, still);
  EXPECT_EQ(ev.contact_give_ups, 1);
  ASSERT_EQ(ev.collisions.size(), 1u);
  EXPECT_EQ(ev.collisions[0].agent, 1);
  EXPECT_EQ(ev.collisions[0].kind, world::ObstacleKind::kMover);
  EXPECT_GT(ev.collisions[0].fraction, 0.0);
  EXPECT_LT(ev.collisions[0].fraction, 1.0);
  EXPECT_EQ(state.contact_give_ups, 1);
  EXPECT_EQ(summarize(state).contact_give_ups, 1);
}

// An episode on the patrol map (spheres and movers) reset from its second scenario: pure pursuit against flee,
// collisions penalized (the game goes on through them).
struct PatrolChase {
  static GameConfig chase() {
    GameConfig c = preset("peg3d");
    c.pursuer.policy = "pure-pursuit";
    c.evader.policy = "flee";
    c.collision = CollisionMode::kPenalize;
    return c;
  }
  std::shared_ptr<const world::Arena> arena =
      world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/maps/patrol.yaml"));
  GameConfig c = chase();
  Sim sim{arena, c};
  SimState st{sim};
  Lineup l = testing::lineup_for(c, arena->map().scenarios[1]);
  PatrolChase() { reset(sim, st, arena->map().scenarios[1], 3); }
};

TEST(Sim, AgentsSenseMoversWhereTheyAreNow) {
  // Every step of an episode on the patrol map: the distance an agent senses (its field, arena faces left
  // out) is within one voxel diagonal of the exact distance to the nearest sphere or mover at that instant.
  PatrolChase game;
  auto& [arena, c, sim, st, l] = game;
  const double diagonal = std::sqrt(3.0) * arena->resolution();
  const double cap = arena->max_distance();
  int near_movers = 0, steps = 0;
  std::vector<Steering> commands(2);
  while (!st.done) {
    for (int i = 0; i < 2; ++i) {
      const Vec3 p = st.agents[std::size_t(i)].kinematics.position;
      double exact = cap;
      for (const auto& s : arena->map().spheres) exact = std::min(exact, std::max(0.0, (p - s.center).norm() - s.radius));
      double mover = cap;
      for (int m = 0; m < sim.movers()->count(); ++m) {
        mover = std::min(mover, nearest_on_shape(sim.movers()->mover(m).shape, sim.movers()->pose(m, st.time), p).distance);
      }
      near_movers += mover < std::min(exact, cap);
      exact = std::min(exact, mover);
      EXPECT_NEAR(observe(st, i).field.distance, exact, diagonal) << "t = " << st.time << ", agent " << i;
      commands[std::size_t(i)] = l[i].act(observe(st, i));
    }
    step(sim, st, commands);
    ++steps;
  }
  EXPECT_GT(steps, 100);
  EXPECT_GT(near_movers, 0);  // movers were the nearest obstacle at some steps
}

TEST(Sim, WithinItsReachTheProbeSensesWhatTheAgentWould) {
  // The guard's look-ahead asks for the obstacle nearest to a point within a reach. Within it, the answer is
  // the full one to the bit; beyond it, the answer lies beyond it too (the guard cannot use it either way).
  PatrolChase game;
  auto& [arena, c, sim, st, l] = game;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  int within = 0, beyond = 0;
  std::vector<Steering> commands(2);
  while (!st.done) {
    for (int i = 0; i < 2; ++i) {
      for (const double reach : {0.5, 1.4, 3.0}) {
        const Vec3 p = arena->bounds().clamp(st.agents[std::size_t(i)].kinematics.position + Vec3(u(rng), u(rng), u(rng)));
        const ObstacleSense full = sense_obstacle(sim, st, p), near = sense_obstacle(sim, st, p, reach);
        if (full.found && full.distance <= reach) {
          ++within;
          EXPECT_EQ(near.distance, full.distance) << "t = " << st.time;
          EXPECT_EQ(near.point, full.point);
          EXPECT_TRUE(near.found);
        } else {
          ++beyond;
          EXPECT_TRUE(!near.found || near.distance > reach) << "t = " << st.time;
        }
      }
      commands[std::size_t(i)] = l[i].act(observe(st, i));
    }
    step(sim, st, commands);
  }
  EXPECT_GT(within, 100);
  EXPECT_GT(beyond, 100);
}

TEST(Sim, OctreeSensingFollowsTheMoversWithinTheFieldsError) {
  // The same episode sensed both ways: the incrementally updated octree EDT agrees with the exact distances
  // within the distance field's documented error (three half voxel diagonals and a voxel).
  const auto arena = crossing_arena(12.0);
  GameConfig c = standing_evader();
  c.time_limit = 3.0;
  c.collision = CollisionMode::kPenalize;
  const Sim exact(arena, c);
  c.mover_sensing = MoverSensing::kOctree;
  const Sim octree(arena, c);
  SimState a(exact), b(octree);
  const auto& s = arena->map().scenarios[0];
  reset(exact, a, s, 1);
  reset(octree, b, s, 1);
  ASSERT_TRUE(b.moving_field != nullptr);
  const double margin = arena->distance_field().error_margin();
  const std::vector<Steering> still(2);
  int compared = 0;
  while (!a.done) {
    for (int i = 0; i < 2; ++i) {
      if (observe(a, i).field.found || observe(b, i).field.found) {
        EXPECT_NEAR(observe(b, i).field.distance, observe(a, i).field.distance, margin) << "t = " << a.time;
        ++compared;
      }
    }
    step(exact, a, still);
    step(octree, b, still);
  }
  EXPECT_GT(compared, 10);
}

TEST(Sim, TheGuardHoldsInTheForest) {
  // The Apollonius interceptor leads its target through gaps between trunks, and a random start heading may
  // begin a game turning in a thicket. With the field's nearest voxel as the guard's only obstacle it hit a
  // trunk in 22 of these 1000 games; the last resort holds against every trunk within reach, exactly.
  const world::MapSpec spec = world::load_map(std::filesystem::path(PEG3D_SOURCE_DIR) / "maps" / "forest.yaml");
  GameConfig c = preset("peg3d");
  c.initial_heading = InitialHeading::kRandom;
  c.pursuer.policy = "apollonius";
  c.evader.policy = "flee";
  const Sim sim(world::Arena::build(spec), c);
  SimState state(sim);
  ApolloniusInterceptor pursuer;
  FleeLineOfSight evader;
  Policy* policies[] = {&pursuer, &evader};
  int games = 0, collisions = 0;
  for (std::uint64_t seed = 0; games < 1000; ++seed) {
    for (const world::Scenario& s : spec.scenarios) {
      const EpisodeResult r = play(sim, state, s, policies, false, seed);
      collisions += r.collisions;
      ++games;
    }
  }
  EXPECT_EQ(collisions, 0) << "in " << games << " games";
}

TEST(Sim, TheGameStepMustBeAWholeNumberOfPhysicsSubsteps) {
  const auto arena = crossing_arena(10.0);
  GameConfig c = standing_evader();
  c.dt = 0.1 + 1.0 / 480.0;  // 24.5 substeps of 1/240 s
  try {
    Sim sim(arena, c);
    ADD_FAILURE() << "accepted";
  } catch (const world::MapError& e) {
    EXPECT_EQ(e.field(), "physics.rate_hz") << e.what();
  }
  c.dt = 0.05;  // 12 substeps
  EXPECT_NO_THROW(Sim(arena, c));
}

TEST(Sim, AStartInsideAMoverIsRefused) {
  world::MapSpec m = crossing_arena(10.0)->map();
  m.scenarios[0].evaders[0].position = Vec3(3.5, 10, 10);  // inside the ball at its start (3, 10, 10)
  EXPECT_THROW(world::Arena::build(m), world::MapError);   // the map holds a start inside a mover
  m.scenarios[0].evaders[0].position = Vec3(3, 11.1, 10);    // outside the ball, but within the agent's radius
  const auto arena = world::Arena::build(m);
  EXPECT_THROW(Sim(arena, standing_evader()), StartError);
}

}  // namespace
}  // namespace peg3d::game
