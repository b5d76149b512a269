#pragma once
// Runs independent jobs 0..count-1 on a pool of threads. Determinism is the caller's half of the contract:
// job(i) must depend only on i (derive its seed with derive_seed(root, {i, ...}), never from the thread)
// and store its result in slot i of storage sized beforehand. Then the results are the same for any
// number of threads, and 1 thread is the reference run.
//
// Stopping early is cooperative: a StopCheck, polled before each index is handed out (and by long jobs at
// cheap points of their own, which then throw RunCancelled), so a sweep can end within a moment of a request.

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace peg3d::sweep {

/// A polled request to stop: true once the caller wants no more work started. Empty: never stops. Called
/// often from every worker thread, so it must be cheap and thread-safe (typically an atomic load).
using StopCheck = std::function<bool()>;

/// Thrown by a job that gave up part-way because its StopCheck asked it to; the job's result is dropped.
class RunCancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "run cancelled on a stop request"; }
};

/// Throws RunCancelled when `stop` asks to stop; for jobs to call between their (short) steps.
inline void throw_if_stopped(const StopCheck& stop) {
  if (stop && stop()) throw RunCancelled();
}

/// Number of worker threads run_indexed uses for `threads`: threads itself when > 0, else the cores this
/// process may run on (its CPU affinity: what taskset, a Slurm allocation or mpirun's binding of a rank
/// leaves it), falling back to the hardware concurrency (1 if unknown).
inline int resolve_thread_count(int threads) {
  if (threads > 0) return threads;
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) == 0 && CPU_COUNT(&allowed) > 0) return CPU_COUNT(&allowed);
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : static_cast<int>(hardware);
}

/// Calls job(i) for every i in [0, count) on resolve_thread_count(threads) worker threads (never more
/// threads than jobs; with one, the jobs run on the calling thread in index order). Indices are handed out
/// in increasing order from one atomic counter. job is shared by all threads and called concurrently with
/// distinct i, so it must be safe to call that way.
///
/// `stop` (optional) is polled before each index is handed out: once it returns true no further index
/// starts; the jobs already running finish (or give up on their own), and run_indexed returns normally. The
/// caller tells which indices ran by what they stored.
///
/// Exceptions: once a job throws, no further indices are handed out; the jobs already started finish, the
/// threads are joined, and the exception of the lowest failing index is rethrown. Because indices are
/// handed out in order, every index below a failing one has been started, so the exception rethrown is
/// the same for any thread count (for jobs whose failure depends only on i). Slots of indices above the
/// failing one may or may not have been filled.
template <class F>
void run_indexed(std::size_t count, int threads, F&& job, const StopCheck& stop = {}) {
  if (count == 0) return;
  const auto workers =
      static_cast<std::size_t>(std::min<long long>(resolve_thread_count(threads), static_cast<long long>(count)));

  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex failure_mutex;
  std::size_t failed_index = std::numeric_limits<std::size_t>::max();
  std::exception_ptr failure;

  const auto work = [&] {
    while (!failed.load(std::memory_order_relaxed)) {
      if (stop && stop()) return;
      const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= count) return;
      try {
        std::invoke(job, i);
      } catch (...) {
        const std::lock_guard lock(failure_mutex);
        if (i < failed_index) {
          failed_index = i;
          failure = std::current_exception();
        }
        failed.store(true, std::memory_order_relaxed);
      }
    }
  };

  if (workers == 1) {
    work();
  } else {
    std::vector<std::jthread> pool;
    pool.reserve(workers);
    for (std::size_t t = 0; t < workers; ++t) pool.emplace_back(work);
    pool.clear();  // joins: every started job has finished
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace peg3d::sweep
