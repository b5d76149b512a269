// The runner every experiment goes through (experiment/experiment.hpp): each run is computed once, into its
// slot, on any thread count; a journal's runs are restored instead of run; finish() comes once, after every
// run, and gathers only on the root.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <vector>

#include "experiment/experiment.hpp"
#include "sweep/run_journal.hpp"

namespace peg3d::experiment {
namespace {

// Run i's result is i * i; the slots, the calls and the order of finish() are what the tests look at.
class Squares : public Experiment {
 public:
  explicit Squares(std::size_t runs) : runs_(runs) {}
  std::string kind() const override { return "squares"; }
  nlohmann::json setup() const override { return {{"experiment", "squares"}}; }
  std::size_t run_count() const override { return runs_; }
  std::size_t episodes_per_run() const override { return 1; }
  void begin(const sweep::SweepControl&) override {
    ++begun;
    slots.assign(runs_, -1);
  }
  void run_one(std::size_t i) override {
    ++computed;
    EXPECT_EQ(finished, 0) << "run " << i << " after finish()";
    slots[i] = static_cast<long>(i * i);
  }
  nlohmann::json encode(std::size_t i) const override { return {{"square", slots[i]}}; }
  void restore(std::size_t i, const nlohmann::json& record) override {
    ++restored;
    slots[i] = record.at("square").get<long>();
  }
  void finish(bool root) override {
    ++finished;
    if (!root) return;
    for (const long v : slots) total += v;
  }
  void write_results(const std::filesystem::path&, const SweepTiming&) const override {}
  std::vector<std::pair<std::string, const world::Arena*>> maps() const override { return {}; }
  nlohmann::ordered_json run_info() const override { return {}; }
  std::string report(const SweepTiming&) const override { return {}; }

  std::vector<long> slots;
  std::atomic<int> computed{0}, restored{0};
  int begun = 0, finished = 0;
  long total = 0;

 private:
  std::size_t runs_;
};

long sum_of_squares(std::size_t n) {
  long sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += static_cast<long>(i * i);
  return sum;
}

TEST(RunExperiment, ComputesEveryRunOnceIntoItsSlotOnAnyThreadCount) {
  for (const int threads : {1, 2, 4}) {
    Squares e(37);
    run_experiment(e, threads, {}, /*root=*/true);
    EXPECT_EQ(e.begun, 1);
    EXPECT_EQ(e.computed, 37) << threads << " threads";
    EXPECT_EQ(e.restored, 0);
    EXPECT_EQ(e.finished, 1);
    EXPECT_EQ(e.total, sum_of_squares(37)) << threads << " threads";
    for (std::size_t i = 0; i < e.slots.size(); ++i) EXPECT_EQ(e.slots[i], static_cast<long>(i * i)) << "slot " << i;
  }
}

TEST(RunExperiment, RestoresTheJournalsRunsAndComputesOnlyTheOthers) {
  const auto file = std::filesystem::path(::testing::TempDir()) / "squares.journal";
  std::filesystem::remove(file);
  Squares first(9);
  {
    const auto journal = sweep::RunJournal::create(file, 9, first.setup());
    for (const std::size_t i : {0u, 4u, 8u}) journal->record(i, {{"square", static_cast<long>(i * i)}});
  }
  const auto journal = sweep::RunJournal::resume(file, 9, first.setup());
  sweep::SweepControl control;
  control.journal = journal.get();
  run_experiment(first, 2, control, /*root=*/true);
  EXPECT_EQ(first.restored, 3);
  EXPECT_EQ(first.computed, 6);
  EXPECT_EQ(first.total, sum_of_squares(9));
  EXPECT_EQ(journal->recorded(), 9u);  // the computed runs were journaled as they finished
  std::filesystem::remove(file);
}

TEST(RunExperiment, FinishesOnEveryProcessButGathersOnlyOnTheRoot) {
  Squares e(5);
  run_experiment(e, 1, {}, /*root=*/false);
  EXPECT_EQ(e.finished, 1);
  EXPECT_EQ(e.total, 0);
}

}  // namespace
}  // namespace peg3d::experiment
