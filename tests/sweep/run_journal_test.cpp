// The run journal (sweep/run_journal.hpp): records read back exactly, a torn last line dropped, a journal of
// another sweep refused naming the field, bad lines named by line; run_indexed hands out no index once stopped.
#include "sweep/run_journal.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "support/input_error_of.hpp"
#include "support/scratch_dir.hpp"
#include "sweep/parallel_runner.hpp"

namespace peg3d::sweep {
namespace {

using peg3d::testing::input_error_of;

namespace fs = std::filesystem;

class SweepRunJournal : public ::testing::Test {
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

TEST_F(SweepRunJournal, RecordsReadBackAfterReopening) {
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

TEST_F(SweepRunJournal, ATornLastLineIsDroppedAndCut) {
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

TEST_F(SweepRunJournal, AJournalOfAnotherSweepIsRefusedNamingTheField) {
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

TEST_F(SweepRunJournal, BadFilesAndLinesAreInputErrorsNamingTheLine) {
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
  e = input_error_of([&] { j->restore(2, [](const nlohmann::json& d) { (void)d.at("evaluation").at(5); }); });
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.field(), "run 2");
  e = input_error_of([&] { j->restore(2, [](const nlohmann::json& d) { (void)d.at("missing"); }); });
  EXPECT_EQ(e.line(), 2);
}

TEST_F(SweepRunJournal, OfTwoSweepsStartedAtOnceIntoOneFolderExactlyOneGetsTheJournal) {
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

TEST(SweepParallelRunnerStop, NoIndexIsHandedOutOnceStopped) {
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
}  // namespace peg3d::sweep
