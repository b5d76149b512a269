#pragma once
// Runs a piece of work that parses untrusted data (a mesh file through a third-party importer) in a forked
// child process that can be stopped: bounded in processor time (and, as a backstop, wall time) and in the
// memory it may add. A hang, a runaway
// allocation or a crash in that code becomes a result the caller can report, never the caller's own.

#include <cstddef>
#include <functional>
#include <string>

namespace peg3d {

struct ChildLimits {
  /// s of processor time the child may use before it is killed, > 0. Processor time, not wall time, so that the
  /// bound does not depend on how loaded the machine is (a sanitized test run on two busy cores imports a mesh
  /// several times slower by the clock). A child that blocks without using the processor is killed after
  /// kWallTimeFactor times as long by the clock.
  double seconds = 8.0;
  std::size_t extra_memory_bytes = std::size_t{768} << 20;  ///< bytes the child may add to the caller's memory
  static constexpr double kWallTimeFactor = 4.0;
};

struct ChildResult {
  enum class Status {
    kOk,        ///< work returned; output holds what it returned
    kFailed,    ///< work threw; output holds the exception's what()
    kTimedOut,  ///< killed after limits.seconds of processor time
    kBlocked,   ///< killed by the clock after kWallTimeFactor * limits.seconds without using that processor time
    kOutOfMemory,  ///< it needed more than limits.extra_memory_bytes (an allocation failed, or it was killed)
    kCrashed,   ///< it died of a signal (output: the signal's name)
  };
  Status status = Status::kCrashed;
  std::string output;
};

/// Forks, runs `work` in the child and returns what it returned (or why it did not). The child's address
/// space is capped (RLIMIT_AS, except under AddressSanitizer, whose shadow memory needs terabytes of it) and
/// its resident memory is watched by the parent, which kills it on either limit. The child leaves with
/// _exit, so no destructors or atexit handlers of the parent's state run twice. Safe from a multi-threaded
/// process as long as `work` takes no lock another thread may hold: glibc's malloc is fork-safe, but GCC 12's
/// AddressSanitizer allocator takes no lock around fork, so a thread allocating as the child is forked can
/// leave it blocked (kBlocked).
ChildResult run_bounded(const std::function<std::string()>& work, const ChildLimits& limits);

}  // namespace peg3d
