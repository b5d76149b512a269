#include "core/bounded_child.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace peg3d {
namespace {

using Status = ChildResult::Status;

TEST(CoreBoundedChild, ReturnsWhatTheWorkReturned) {
  const std::string big(3 << 20, 'x');  // more than a pipe holds: the parent must read while the child writes
  const ChildResult r = run_bounded([&] { return big + "!"; }, {});
  EXPECT_EQ(r.status, Status::kOk);
  EXPECT_EQ(r.output, big + "!");
}

TEST(CoreBoundedChild, AnExceptionIsAFailureWithItsMessage) {
  const ChildResult r = run_bounded([]() -> std::string { throw std::runtime_error("no triangles"); }, {});
  EXPECT_EQ(r.status, Status::kFailed);
  EXPECT_EQ(r.output, "no triangles");
}

// The processor time of this process's reaped children, in s.
double children_cpu_seconds() {
  rusage u{};
  ::getrusage(RUSAGE_CHILDREN, &u);
  const auto s = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return s(u.ru_utime) + s(u.ru_stime);
}

TEST(CoreBoundedChild, ABusyLoopIsKilledOnceItHasUsedItsProcessorTime) {
  const double before = children_cpu_seconds();
  const ChildResult r = run_bounded(
      []() -> std::string {
        volatile unsigned long spins = 0;
        for (;;) spins = spins + 1;
      },
      {0.3, std::size_t{256} << 20});
  EXPECT_EQ(r.status, Status::kTimedOut);
  // Killed by its processor time, not by the wall-clock backstop (which would let it run 1.2 s).
  const double used = children_cpu_seconds() - before;
  EXPECT_GE(used, 0.3);
  EXPECT_LT(used, 0.9);
}

TEST(CoreBoundedChild, AChildBlockedOffTheProcessorIsKilledByTheWallClockBackstop) {
  const auto start = std::chrono::steady_clock::now();
  const ChildResult r = run_bounded([]() -> std::string { for (;;) ::pause(); }, {0.3, std::size_t{256} << 20});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.status, Status::kBlocked);
  EXPECT_GE(seconds, 0.3 * ChildLimits::kWallTimeFactor);
  EXPECT_LT(seconds, 0.3 * ChildLimits::kWallTimeFactor + 3.0);
}

TEST(CoreBoundedChild, MemoryBeyondTheLimitStopsTheChild) {
  // Touch every page so the resident set grows even where the address space is not capped (ASan builds).
  const ChildResult r = run_bounded(
      []() -> std::string {
        std::vector<std::vector<char>> hog;
        for (;;) {
          hog.emplace_back(std::size_t{16} << 20);
          std::memset(hog.back().data(), 1, hog.back().size());
        }
      },
      {20.0, std::size_t{128} << 20});
  EXPECT_EQ(r.status, Status::kOutOfMemory);
}

TEST(CoreBoundedChild, ACrashIsReportedWithItsSignal) {
  // The default action, so that a sanitizer's SEGV handler (which exits instead) does not change the outcome.
  const ChildResult r = run_bounded(
      []() -> std::string {
        std::signal(SIGSEGV, SIG_DFL);
        std::raise(SIGSEGV);
        return "";
      },
      {});
  EXPECT_EQ(r.status, Status::kCrashed);
  EXPECT_EQ(r.output, "SIGSEGV");
}

TEST(CoreBoundedChild, AnExitWithoutAResultIsACrashWithItsStatus) {
  const ChildResult r = run_bounded([]() -> std::string { ::_exit(3); }, {});
  EXPECT_EQ(r.status, Status::kCrashed);
  EXPECT_EQ(r.output, "exited with status 3 without a result");
}

}  // namespace
}  // namespace peg3d
