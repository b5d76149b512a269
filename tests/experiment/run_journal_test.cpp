// The run journal (experiment/run_journal.hpp): records read back exactly, a torn last line dropped, a journal
// of another sweep refused naming the field, bad lines named by line; run_journaled reruns only the missing
// runs and stops on request; run_indexed hands out no index once stopped.
#include "experiment/run_journal.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "game/game_config.hpp"
#include "game/lineup.hpp"
#include "game/policy_io.hpp"
#include "support/input_error_of.hpp"
#include "support/scratch_dir.hpp"

namespace peg3d::experiment {
namespace {

using peg3d::testing::input_error_of;

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

class ExperimentRunJournal : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = dir_ / kJournalFileName;
  }

  std::string text() const {
    std::ifstream in(file_, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  void append(const std::string& bytes) const {
    std::ofstream out(file_, std::ios::binary | std::ios::app);
    out << bytes;
  }

  static nlohmann::json setup(std::uint64_t seed = 7) {
    return {{"experiment", "test"}, {"seed", seed}, {"config", {{"dt", 0.05}, {"name", "peg3d"}}}};
  }


  peg3d::testing::ScratchDir scratch_;  // before dir_, which copies its path
  fs::path dir_ = scratch_.path(), file_;
};

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

TEST(ExperimentRunJournalCodecs, EpisodesRoundTripToTheBitThroughText) {
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

TEST(ExperimentRunJournalCodecs, TracesSummariesAndModelsRoundTrip) {
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
  }
  ASSERT_EQ(r.captures.size(), 1u);
  EXPECT_EQ(r.captures[0].distance, 0.49);

  game::AgentSummary s{game::Role::kEvader, 1, 33.5, -2.25, 400, 0.125, 1, 0, -1.0};
  const game::AgentSummary s2 = agent_summary_from_json(nlohmann::json::parse(agent_summary_to_json(s).dump()));
  EXPECT_EQ(s2.role, s.role);
  EXPECT_EQ(s2.path, s.path);
  EXPECT_EQ(s2.captured_at, s.captured_at);

  game::Lineup lineup;
  game::RoleModels models;
  game::add_configured(lineup, game::preset("peg3d"), game::Role::kPursuer, 1, 5, &models);
  ASSERT_FALSE(models.empty());
  const game::RoleModels back =
      role_models_from_json(nlohmann::json::parse(role_models_to_json(models).dump()), game::Role::kPursuer);
  ASSERT_EQ(back.models.size(), models.models.size());
  EXPECT_EQ(back.of_agent, models.of_agent);
  EXPECT_EQ(game::policy_to_json(*back.models[0]), game::policy_to_json(*models.models[0]));
  EXPECT_THROW(role_models_from_json(role_models_to_json(models), game::Role::kEvader), InputError);
}

TEST_F(ExperimentRunJournal, RecordsReadBackAfterReopening) {
  {
    auto j = RunJournal::create(file_, 5, setup());
    j->record(3, {{"x", 0.1 + 0.2}});
    j->record(0, {{"x", -1}});
    EXPECT_EQ(j->recorded(), 2u);
    EXPECT_THROW(j->record(3, {}), std::logic_error);  // never twice
    EXPECT_THROW(j->record(5, {}), std::logic_error);  // out of range
  }
  auto j = RunJournal::resume(file_, 5, setup());
  EXPECT_FALSE(j->dropped_torn_line());
  EXPECT_EQ(j->recorded(), 2u);
  EXPECT_TRUE(j->has(0));
  EXPECT_TRUE(j->has(3));
  EXPECT_FALSE(j->has(1));
  double x = 0.0;
  j->restore(3, [&](const nlohmann::json& d) { x = d.at("x").get<double>(); });
  EXPECT_EQ(x, 0.1 + 0.2);
  EXPECT_THROW(j->restore(1, [](const nlohmann::json&) {}), std::logic_error);
  // Appends go on after the lines read back.
  j->record(1, {{"x", 2}});
  j.reset();
  EXPECT_EQ(RunJournal::resume(file_, 5, setup())->recorded(), 3u);
}

TEST_F(ExperimentRunJournal, ATornLastLineIsDroppedAndCut) {
  {
    auto j = RunJournal::create(file_, 4, setup());
    j->record(2, {{"x", 1}});
  }
  const std::string whole = text();
  append(R"({"run":1,"data":{"x":)");  // a crash in the middle of a line
  {
    auto j = RunJournal::resume(file_, 4, setup());
    EXPECT_TRUE(j->dropped_torn_line());
    EXPECT_EQ(j->recorded(), 1u);
    EXPECT_FALSE(j->has(1));
    EXPECT_EQ(text(), whole);  // cut, so the next line starts on a fresh one
    j->record(1, {{"x", 5}});
  }
  auto j = RunJournal::resume(file_, 4, setup());
  EXPECT_FALSE(j->dropped_torn_line());
  EXPECT_EQ(j->recorded(), 2u);

  // A whole line whose newline did not make it is dropped too (the run simply reruns).
  j.reset();
  append(R"({"run":3,"data":{"x":1}})");
  EXPECT_EQ(RunJournal::resume(file_, 4, setup())->recorded(), 2u);
}

TEST_F(ExperimentRunJournal, AJournalOfAnotherSweepIsRefusedNamingTheField) {
  RunJournal::create(file_, 4, setup(7))->record(0, {});
  const std::string before = text();
  InputError e = input_error_of([&] { RunJournal::resume(file_, 4, setup(8)); });
  EXPECT_EQ(e.file(), file_);
  EXPECT_EQ(e.line(), 1);
  EXPECT_EQ(e.field(), "setup.seed");
  EXPECT_NE(std::string(e.what()).find("7"), std::string::npos) << e.what();

  nlohmann::json other = setup();
  other["config"]["dt"] = 0.1;
  e = input_error_of([&] { RunJournal::resume(file_, 4, other); });
  EXPECT_EQ(e.field(), "setup.config.dt");
  other = setup();
  other["extra"] = true;
  e = input_error_of([&] { RunJournal::resume(file_, 4, other); });
  EXPECT_EQ(e.field(), "setup.extra");
  e = input_error_of([&] { RunJournal::resume(file_, 5, setup()); });
  EXPECT_EQ(e.field(), "runs");
  EXPECT_EQ(text(), before);  // a refused journal is left as it was

  // Starting a new sweep over it is refused too: runs of two sweeps are never mixed.
  e = input_error_of([&] { RunJournal::create(file_, 4, setup()); });
  EXPECT_EQ(e.file(), file_);
  EXPECT_EQ(text(), before);
}

TEST_F(ExperimentRunJournal, BadFilesAndLinesAreInputErrorsNamingTheLine) {
  EXPECT_NE(std::string(input_error_of([&] { RunJournal::resume(file_, 4, setup()); }).what()).find("no journal"),
            std::string::npos);
  append("{\"format\":\"peg3d-policy\"}\n");
  EXPECT_EQ(input_error_of([&] { RunJournal::resume(file_, 4, setup()); }).field(), "format");
  fs::remove(file_);

  RunJournal::create(file_, 4, setup());
  append("{\"run\":0,\"data\":{}}\nnot json\n{\"run\":1,\"data\":{}}\n");
  InputError e = input_error_of([&] { RunJournal::resume(file_, 4, setup()); });
  EXPECT_EQ(e.line(), 3);
  fs::remove(file_);

  RunJournal::create(file_, 4, setup());
  append("{\"run\":9,\"data\":{}}\n{\"run\":1,\"data\":{}}\n");
  e = input_error_of([&] { RunJournal::resume(file_, 4, setup()); });
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.field(), "run");
  fs::remove(file_);

  RunJournal::create(file_, 4, setup());
  append("{\"run\":1,\"data\":{}}\n{\"run\":1,\"data\":{}}\n{\"run\":2,\"data\":{}}\n");
  e = input_error_of([&] { RunJournal::resume(file_, 4, setup()); });
  EXPECT_EQ(e.line(), 3);
  EXPECT_NE(std::string(e.what()).find("twice"), std::string::npos) << e.what();
  fs::remove(file_);

  // A record that does not decode names its line and run.
  RunJournal::create(file_, 4, setup());
  append("{\"run\":2,\"data\":{\"evaluation\":[1,2]}}\n");
  auto j = RunJournal::resume(file_, 4, setup());
  e = input_error_of([&] { j->restore(2, [](const nlohmann::json& d) { episode_from_json(d.at("evaluation")); }); });
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.field(), "run 2");
  e = input_error_of([&] { j->restore(2, [](const nlohmann::json& d) { (void)d.at("missing"); }); });
  EXPECT_EQ(e.line(), 2);
}

TEST_F(ExperimentRunJournal, OfTwoSweepsStartedAtOnceIntoOneFolderExactlyOneGetsTheJournal) {
  for (int round = 0; round < 50; ++round) {
    std::filesystem::remove(file_);
    std::atomic<int> created{0}, refused{0}, winner{-1};
    std::atomic<bool> go{false};
    {
      std::vector<std::jthread> sweeps;
      for (int k = 0; k < 4; ++k) {
        sweeps.emplace_back([&, k] {
          while (!go.load()) std::this_thread::yield();
          try {
            RunJournal::create(file_, 10, setup(static_cast<std::uint64_t>(k)));
            ++created;
            winner = k;
          } catch (const InputError&) {
            ++refused;
          }
        });
      }
      go = true;
    }
    ASSERT_EQ(created.load(), 1) << "round " << round;
    ASSERT_EQ(refused.load(), 3) << "round " << round;
    // The one journal is whole and nothing staged is left beside it.
    EXPECT_NO_THROW(RunJournal::resume(file_, 10, setup(static_cast<std::uint64_t>(winner.load()))).reset())
        << "round " << round;
    int files = 0;
    for ([[maybe_unused]] const auto& f : std::filesystem::directory_iterator(dir_)) ++files;
    EXPECT_EQ(files, 1);
  }
}

TEST_F(ExperimentRunJournal, SweepsRerunOnlyTheMissingRunsAndStopOnRequest) {
  constexpr std::size_t kRuns = 40;
  const auto value = [](std::size_t i) { return static_cast<double>(i * i) / 3.0; };
  std::atomic<bool> stop{false};
  std::atomic<int> ran{0};
  {
    auto j = RunJournal::create(file_, kRuns, setup());
    std::vector<double> out(kRuns, -1.0);
    const SweepControl control{j.get(), [&] { return stop.load(); }};
    try {
      run_journaled(
          kRuns, 2, control,
          [&](std::size_t i) {
            if (ran.fetch_add(1) == 10) stop = true;
            throw_if_stopped(control.stop);  // a run in flight gives up
            out[i] = value(i);
          },
          [&](std::size_t i) { return nlohmann::json{{"v", out[i]}}; },
          [&](std::size_t, const nlohmann::json&) { ADD_FAILURE() << "nothing to restore"; });
      ADD_FAILURE() << "no SweepInterrupted";
    } catch (const SweepInterrupted& e) {
      EXPECT_EQ(e.total(), kRuns);
      EXPECT_EQ(e.kept(), j->recorded());
      EXPECT_EQ(e.journal(), file_);
      EXPECT_GE(e.kept(), 9u);
      EXPECT_LE(e.kept(), 11u);  // no run starts once stopped: at most the two in flight
    }
  }
  stop = false;
  auto j = RunJournal::resume(file_, kRuns, setup());
  const std::size_t kept = j->recorded();
  std::vector<double> out(kRuns, -1.0);
  std::atomic<std::size_t> reran{0}, restored{0};
  run_journaled(
      kRuns, 1, {j.get(), {}},
      [&](std::size_t i) {
        EXPECT_FALSE(j->has(i));
        out[i] = value(i);
        ++reran;
      },
      [&](std::size_t i) { return nlohmann::json{{"v", out[i]}}; },
      [&](std::size_t i, const nlohmann::json& d) {
        out[i] = d.at("v").get<double>();
        ++restored;
      });
  EXPECT_EQ(restored.load(), kept);
  EXPECT_EQ(reran.load(), kRuns - kept);
  for (std::size_t i = 0; i < kRuns; ++i) EXPECT_EQ(out[i], value(i)) << i;
  EXPECT_EQ(j->recorded(), kRuns);
  j->remove();
  EXPECT_FALSE(fs::exists(file_));
}

TEST(ExperimentParallelRunnerStop, NoIndexIsHandedOutOnceStopped) {
  for (const int threads : {1, 2}) {
    std::atomic<int> calls{0}, after_stop{0};
    std::atomic<bool> stop{false};
    run_indexed(
        1000, threads,
        [&](std::size_t i) {
          ++calls;
          if (stop) ++after_stop;
          if (i == 5) stop = true;
        },
        [&] { return stop.load(); });
    // Only a worker that had passed the check when the flag rose may start one more job.
    EXPECT_LE(after_stop.load(), threads - 1) << threads << " threads";
    EXPECT_LT(calls.load(), 1000);
    if (threads == 1) {
      EXPECT_EQ(calls.load(), 6);
    }
  }
}

}  // namespace
}  // namespace peg3d::experiment
