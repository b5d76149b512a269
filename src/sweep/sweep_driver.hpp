#pragma once
// The sweep driver: runs 0..count-1 on this process's threads or over a process group, through the journal
// (run_journal.hpp) so that an interrupted sweep keeps its finished runs and --resume reruns only the others.

#include <cstddef>
#include <filesystem>
#include <stdexcept>

#include "sweep/sweep_control.hpp"

namespace peg3d::sweep {

/// A sweep stopped (by its StopCheck) before every run finished. The runs kept are in the journal (when
/// there is one); no final file was written.
class SweepInterrupted : public std::runtime_error {
 public:
  SweepInterrupted(std::size_t kept, std::size_t total, std::filesystem::path journal);
  std::size_t kept() const noexcept { return kept_; }
  std::size_t total() const noexcept { return total_; }
  /// The journal holding the kept runs; empty when the sweep had none (the runs are then lost).
  const std::filesystem::path& journal() const noexcept { return journal_; }

 private:
  std::size_t kept_, total_;
  std::filesystem::path journal_;
};

/// Runs 0..count-1 as run_indexed does (same threads and determinism), through `control`:
/// - the runs the journal holds are handed to runs.restore(i, record), in index order, before any run starts;
/// - every other run is computed by runs.run(i) and, once it returns, runs.encode(i) is appended to the journal;
/// - on a stop request no further run starts, runs in flight give up (run throws RunCancelled) and are
///   dropped, and SweepInterrupted is thrown once the threads are joined, unless every run finished anyway.
/// encode is not called without a journal. Other exceptions of run propagate as in run_indexed.
///
/// With a group of several processes (control.group), every rank calls this with the same arguments but
/// `threads`: the runs are spread over the ranks as in run_distributed (distributed_sweep.hpp), and on the
/// root every run ends up in its slot exactly as in a single-process sweep, computed there or restored from
/// another rank's encode(i). The other ranks return once the root needs them no more; their slots are not
/// all filled.
void run_sweep(std::size_t count, int threads, const SweepControl& control, const SweepRuns& runs);

}  // namespace peg3d::sweep
