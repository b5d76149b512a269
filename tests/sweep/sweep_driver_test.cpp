// The sweep driver (sweep/sweep_driver.hpp): an interrupted sweep keeps its finished runs in the journal, and
// the sweep resumed from it reruns only the missing runs, with every slot as an uninterrupted sweep fills it.
#include "sweep/sweep_driver.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <vector>

#include "support/scratch_dir.hpp"
#include "sweep/run_journal.hpp"

namespace peg3d::sweep {
namespace {

namespace fs = std::filesystem;

class SweepDriver : public ::testing::Test {
 protected:
  static nlohmann::json setup() { return {{"experiment", "test"}, {"seed", 7}}; }

  peg3d::testing::ScratchDir scratch_;
  fs::path file_ = scratch_.path() / kJournalFileName;
};

TEST_F(SweepDriver, SweepsRerunOnlyTheMissingRunsAndStopOnRequest) {
  constexpr std::size_t kRuns = 40;
  const auto value = [](std::size_t i) { return static_cast<double>(i * i) / 3.0; };
  std::atomic<bool> stop{false};
  std::atomic<int> ran{0};
  {
    auto j = RunJournal::create(file_, kRuns, setup());
    std::vector<double> out(kRuns, -1.0);
    const SweepControl control{j.get(), [&] { return stop.load(); }};
    try {
      run_sweep(kRuns, 2, control,
                {.run =
                     [&](std::size_t i) {
                       if (ran.fetch_add(1) == 10) stop = true;
                       throw_if_stopped(control.stop);  // a run in flight gives up
                       out[i] = value(i);
                     },
                 .encode = [&](std::size_t i) { return nlohmann::json{{"v", out[i]}}; },
                 .restore = [&](std::size_t, const nlohmann::json&) { ADD_FAILURE() << "nothing to restore"; }});
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
  run_sweep(kRuns, 1, {j.get(), {}},
            {.run =
                 [&](std::size_t i) {
                   EXPECT_FALSE(j->has(i));
                   out[i] = value(i);
                   ++reran;
                 },
             .encode = [&](std::size_t i) { return nlohmann::json{{"v", out[i]}}; },
             .restore = [&](std::size_t i, const nlohmann::json& d) {
               out[i] = d.at("v").get<double>();
               ++restored;
             }});
  EXPECT_EQ(restored.load(), kept);
  EXPECT_EQ(reran.load(), kRuns - kept);
  for (std::size_t i = 0; i < kRuns; ++i) EXPECT_EQ(out[i], value(i)) << i;
  EXPECT_EQ(j->recorded(), kRuns);
  j->remove();
  EXPECT_FALSE(fs::exists(file_));
}

}  // namespace
}  // namespace peg3d::sweep
