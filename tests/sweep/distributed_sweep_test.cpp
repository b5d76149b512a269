// A sweep spread over a process group (sweep/distributed_sweep.hpp), with threads standing in for MPI
// ranks: the root ends up with every run exactly as a single-process sweep computes it, whatever the ranks and
// threads; every rank computes some; the root's journal records remote runs and resumes on another rank count;
// a failure on another rank reaches the root naming run and rank; a rank asked to stop takes no more runs.
#include "sweep/distributed_sweep.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/random.hpp"
#include "support/scratch_dir.hpp"
#include "sweep/process_group.hpp"
#include "sweep/progress_reporter.hpp"
#include "sweep/run_journal.hpp"
#include "sweep/sweep_driver.hpp"

namespace peg3d::sweep {
namespace {

// Mailboxes shared by the ranks of one in-process group.
struct Hub {
  explicit Hub(int ranks) : boxes(static_cast<std::size_t>(ranks)) {}
  struct Box {
    std::mutex m;
    std::condition_variable cv;
    std::deque<GroupMessage> messages;
  };
  std::vector<Box> boxes;
};

class ThreadRank : public ProcessGroup {
 public:
  ThreadRank(std::shared_ptr<Hub> hub, int rank) : hub_(std::move(hub)), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return static_cast<int>(hub_->boxes.size()); }
  void send(int to, const std::string& bytes) override {
    Hub::Box& box = hub_->boxes[static_cast<std::size_t>(to)];
    const std::lock_guard lock(box.m);
    box.messages.push_back({rank_, bytes});
    box.cv.notify_one();
  }
  GroupMessage receive() override {
    Hub::Box& box = hub_->boxes[static_cast<std::size_t>(rank_)];
    std::unique_lock lock(box.m);
    box.cv.wait(lock, [&] { return !box.messages.empty(); });
    GroupMessage m = std::move(box.messages.front());
    box.messages.pop_front();
    return m;
  }
  Failure agree(int) override { throw std::logic_error("not used by the sweep"); }
  [[noreturn]] void abort(int) override { std::terminate(); }

 private:
  std::shared_ptr<Hub> hub_;
  int rank_;
};

// A run's result: a few numbers of its own seeded engine, and which rank computed it.
struct Slot {
  double value = 0.0;
  int rank = -1;
};

double job_value(std::size_t i) {
  Rng rng(derive_seed(99, {i}));
  std::normal_distribution<double> noise;
  double sum = 0.0;
  for (int k = 0; k < 50; ++k) sum += noise(rng);
  return sum;
}

struct RankSetup {
  int threads = 1;
  StopCheck stop;
  RunJournal* journal = nullptr;  // root only
  ProgressReporter* progress = nullptr;
  std::function<void(std::size_t, int)> before_run;  // (run, rank): may throw, sleep, ...
};

struct RankOutcome {
  std::vector<Slot> slots;
  std::exception_ptr error;
};

// Runs a sweep of `count` runs on `ranks` in-process ranks configured by setup(rank).
std::vector<RankOutcome> sweep(std::size_t count, int ranks, const std::function<RankSetup(int)>& setup) {
  auto hub = std::make_shared<Hub>(ranks);
  std::vector<RankOutcome> out(static_cast<std::size_t>(ranks));
  {
    std::vector<std::jthread> processes;
    for (int r = 0; r < ranks; ++r) {
      processes.emplace_back([&, r] {
        ThreadRank group(hub, r);
        const RankSetup s = setup(r);
        RankOutcome& o = out[static_cast<std::size_t>(r)];
        o.slots.assign(count, {});
        try {
          run_sweep(count, s.threads, {s.journal, s.stop, &group, s.progress},
                    {.run =
                         [&](std::size_t i) {
                           if (s.before_run) s.before_run(i, r);
                           o.slots[i] = {job_value(i), r};
                           if (s.progress) s.progress->episode_done(3), s.progress->run_done();
                         },
                     .encode = [&](std::size_t i) { return nlohmann::json{{"value", o.slots[i].value}, {"rank", o.slots[i].rank}}; },
                     .restore = [&](std::size_t i, const nlohmann::json& data) {
                       o.slots[i] = {data.at("value").get<double>(), data.at("rank").get<int>()};
                     }});
        } catch (...) {
          o.error = std::current_exception();
        }
      });
    }
  }
  return out;
}

void expect_all_runs(const std::vector<Slot>& slots) {
  for (std::size_t i = 0; i < slots.size(); ++i) {
    ASSERT_EQ(slots[i].value, job_value(i)) << "run " << i;  // bit for bit
  }
}

void pause_briefly(std::size_t, int) { std::this_thread::sleep_for(std::chrono::microseconds(300)); }

TEST(SweepDistributedSweep, TheRootHoldsEveryRunAsOneProcessComputesIt) {
  for (const auto& [ranks, threads] : {std::pair{2, 1}, std::pair{3, 2}, std::pair{5, 1}}) {
    SCOPED_TRACE(::testing::Message() << ranks << " ranks of " << threads << " threads");
    const auto out = sweep(200, ranks, [&](int) { return RankSetup{threads, {}, nullptr, nullptr, pause_briefly}; });
    for (const auto& o : out) ASSERT_FALSE(o.error);
    expect_all_runs(out[0].slots);
    std::vector<int> per_rank(static_cast<std::size_t>(ranks), 0);
    for (const Slot& s : out[0].slots) ++per_rank[static_cast<std::size_t>(s.rank)];
    for (int r = 0; r < ranks; ++r) EXPECT_GT(per_rank[static_cast<std::size_t>(r)], 0) << "rank " << r << " ran nothing";
  }
}

TEST(SweepDistributedSweep, TheRootCountsEveryRanksProgress) {
  ProgressReporter progress(100, 300, nullptr);
  std::vector<std::unique_ptr<ProgressReporter>> counters;
  for (int r = 1; r < 3; ++r) counters.push_back(std::make_unique<ProgressReporter>(0, 0, nullptr));
  const auto out = sweep(100, 3, [&](int r) {
    return RankSetup{1, {}, nullptr, r == 0 ? &progress : counters[static_cast<std::size_t>(r - 1)].get(), pause_briefly};
  });
  ASSERT_FALSE(out[0].error);
  EXPECT_EQ(progress.snapshot().runs_done, 100u);
  EXPECT_EQ(progress.snapshot().episodes_done, 300u);
}

TEST(SweepDistributedSweep, TheRootsJournalRecordsRemoteRunsAndResumesOnAnotherRankCount) {
  peg3d::testing::ScratchDir dir;
  const auto file = dir / kJournalFileName;
  const nlohmann::json setup{{"experiment", "test"}};
  // Stopped by the root once 30 runs are in its journal.
  {
    auto journal = RunJournal::create(file, 120, setup);
    std::atomic<bool> stop{false};
    const auto out = sweep(120, 3, [&](int r) {
      RankSetup s{1, {}, r == 0 ? journal.get() : nullptr, nullptr, pause_briefly};
      if (r == 0) s.stop = [&] { return stop.load() || (journal->recorded() >= 30 && (stop = true)); };
      return s;
    });
    ASSERT_TRUE(out[0].error);
    EXPECT_THROW(std::rethrow_exception(out[0].error), SweepInterrupted);
    for (int r = 1; r < 3; ++r) EXPECT_FALSE(out[static_cast<std::size_t>(r)].error) << "rank " << r;
    EXPECT_GE(journal->recorded(), 30u);
    EXPECT_LT(journal->recorded(), 120u);
  }
  // Finished on two ranks: the runs of both sessions, all exact; none of the first is computed again.
  auto journal = RunJournal::resume(file, 120, setup);
  const std::size_t kept = journal->recorded();
  std::atomic<std::size_t> computed{0};
  const auto out = sweep(120, 2, [&](int r) {
    return RankSetup{1, {}, r == 0 ? journal.get() : nullptr, nullptr,
                     [&](std::size_t, int) { computed.fetch_add(1); }};
  });
  ASSERT_FALSE(out[0].error);
  expect_all_runs(out[0].slots);
  EXPECT_EQ(computed.load(), 120u - kept);
  EXPECT_EQ(journal->recorded(), 120u);
}

TEST(SweepDistributedSweep, AFailureOnAnotherRankReachesTheRootNamingRunAndRank) {
  const auto out = sweep(60, 2, [&](int) {
    return RankSetup{1, {}, nullptr, nullptr, [](std::size_t i, int rank) {
                       pause_briefly(i, rank);
                       if (rank == 1) throw std::runtime_error("the disk is on fire");
                     }};
  });
  ASSERT_TRUE(out[0].error);
  try {
    std::rethrow_exception(out[0].error);
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("on rank 1: the disk is on fire"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(out[1].error);  // the failing rank reported and returned
}

TEST(SweepDistributedSweep, ARankAskedToStopTakesNoMoreRunsAndTheOthersFinish) {
  std::atomic<bool> rank1_stopped{false};
  const auto out = sweep(80, 3, [&](int r) {
    RankSetup s{1, {}, nullptr, nullptr, pause_briefly};
    if (r == 1) s.stop = [&] { return rank1_stopped.load(); };
    if (r == 1) s.before_run = [&](std::size_t, int) { rank1_stopped = true; };
    return s;
  });
  ASSERT_FALSE(out[0].error);
  expect_all_runs(out[0].slots);  // the other ranks did rank 1's share
  ASSERT_TRUE(out[1].error);
  EXPECT_THROW(std::rethrow_exception(out[1].error), SweepInterrupted);
}

}  // namespace
}  // namespace peg3d::sweep
