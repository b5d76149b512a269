#include "sweep/parallel_runner.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/random.hpp"

namespace peg3d::sweep {
namespace {

// A job whose result depends only on its index, the way an experiment run does: its own seeded engine.
std::vector<double> simulate(std::size_t count, int threads) {
  std::vector<double> results(count);
  run_indexed(count, threads, [&results](std::size_t i) {
    Rng rng(derive_seed(2024, {i}));
    std::normal_distribution<double> noise;
    double sum = 0.0;
    for (int k = 0; k < 100; ++k) sum += noise(rng);
    results[i] = sum;
  });
  return results;
}

TEST(SweepParallelRunner, ResultsDoNotDependOnThreadCount) {
  const std::vector<double> reference = simulate(500, 1);
  EXPECT_EQ(simulate(500, 2), reference);
  EXPECT_EQ(simulate(500, 7), reference);
  EXPECT_EQ(simulate(500, 0), reference);  // hardware concurrency
}

TEST(SweepParallelRunner, EveryIndexRunsExactlyOnce) {
  constexpr std::size_t kCount = 10000;
  std::vector<std::atomic<int>> calls(kCount);
  run_indexed(kCount, 7, [&calls](std::size_t i) { calls[i].fetch_add(1); });
  for (std::size_t i = 0; i < kCount; ++i) ASSERT_EQ(calls[i].load(), 1) << "index " << i;
}

TEST(SweepParallelRunner, NoJobsMeansNoCalls) {
  bool called = false;
  run_indexed(0, 4, [&called](std::size_t) { called = true; });
  EXPECT_FALSE(called);
}

// Two jobs that each wait (at most `patience`) for the other to start: both meet only when they run at once.
bool jobs_meet(int threads, std::chrono::milliseconds patience) {
  std::mutex m;
  std::condition_variable cv;
  int arrived = 0;
  std::atomic<int> met{0};
  run_indexed(2, threads, [&](std::size_t) {
    std::unique_lock lock(m);
    ++arrived;
    cv.notify_all();
    if (cv.wait_for(lock, patience, [&] { return arrived == 2; })) ++met;
  });
  return met == 2;
}

TEST(SweepParallelRunner, RunsJobsConcurrently) {
  EXPECT_TRUE(jobs_meet(2, std::chrono::seconds(20)));
  // The check can fail without hanging: on one thread the jobs run one after the other and never meet.
  EXPECT_FALSE(jobs_meet(1, std::chrono::milliseconds(50)));
}

TEST(SweepParallelRunner, RethrowsExceptionOfLowestFailingIndex) {
  for (const int threads : {1, 2, 7}) {
    std::vector<std::atomic<bool>> ran(100);
    try {
      run_indexed(ran.size(), threads, [&ran](std::size_t i) {
        ran[i] = true;
        if (i == 30 || i == 60) throw std::runtime_error("job " + std::to_string(i));
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "job 30") << threads << " threads";
    }
    for (std::size_t i = 0; i <= 30; ++i) EXPECT_TRUE(ran[i]) << "index " << i << ", " << threads << " threads";
  }
}

TEST(SweepParallelRunner, RethrowsNonStandardExceptions) {
  EXPECT_THROW(run_indexed(10, 3, [](std::size_t i) {
                 if (i == 4) throw 42;
               }),
               int);
}

TEST(SweepParallelRunner, ResolvesThreadCount) {
  EXPECT_EQ(resolve_thread_count(3), 3);
  EXPECT_GE(resolve_thread_count(0), 1);
  EXPECT_GE(resolve_thread_count(-1), 1);
}

}  // namespace
}  // namespace peg3d::sweep
