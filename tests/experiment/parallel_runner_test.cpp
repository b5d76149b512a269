#include "experiment/parallel_runner.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <latch>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/random.hpp"

namespace peg3d::experiment {
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

TEST(ExperimentParallelRunner, ResultsDoNotDependOnThreadCount) {
  const std::vector<double> reference = simulate(500, 1);
  EXPECT_EQ(simulate(500, 2), reference);
  EXPECT_EQ(simulate(500, 7), reference);
  EXPECT_EQ(simulate(500, 0), reference);  // hardware concurrency
}

TEST(ExperimentParallelRunner, EveryIndexRunsExactlyOnce) {
  constexpr std::size_t kCount = 10000;
  std::vector<std::atomic<int>> calls(kCount);
  run_indexed(kCount, 7, [&calls](std::size_t i) { calls[i].fetch_add(1); });
  for (std::size_t i = 0; i < kCount; ++i) ASSERT_EQ(calls[i].load(), 1) << "index " << i;
}

TEST(ExperimentParallelRunner, NoJobsMeansNoCalls) {
  bool called = false;
  run_indexed(0, 4, [&called](std::size_t) { called = true; });
  EXPECT_FALSE(called);
}

TEST(ExperimentParallelRunner, RunsJobsConcurrently) {
  // Each of the two jobs waits for the other: this finishes only if they run on two threads at once.
  std::latch both(2);
  run_indexed(2, 2, [&both](std::size_t) { both.arrive_and_wait(); });
  SUCCEED();
}

TEST(ExperimentParallelRunner, RethrowsExceptionOfLowestFailingIndex) {
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

TEST(ExperimentParallelRunner, RethrowsNonStandardExceptions) {
  EXPECT_THROW(run_indexed(10, 3, [](std::size_t i) {
                 if (i == 4) throw 42;
               }),
               int);
}

TEST(ExperimentParallelRunner, ResolvesThreadCount) {
  EXPECT_EQ(resolve_thread_count(3), 3);
  EXPECT_GE(resolve_thread_count(0), 1);
  EXPECT_GE(resolve_thread_count(-1), 1);
}

}  // namespace
}  // namespace peg3d::experiment
