#pragma once
// A sweep's runs spread over the ranks of a ProcessGroup (MPI), pulled one at a time so that fast and slow
// runs balance out over ranks of any speed.
//
// The root (rank 0) owns the list of runs to compute and hands them out in increasing order from one
// counter, to its own worker threads and, on request, to the other ranks' threads. Every other rank runs
// `threads` worker threads; each asks the root for a run, computes it, and sends encode(i) back with its
// next request. The root restores what it receives with restore(i, data), the very path a journal's runs
// take on --resume, records it in the journal and counts it. Runs depend only on their index and the codecs
// are exact (results/codecs.hpp), so the root ends up with the results of a single-process sweep, bit for bit,
// whatever the number of ranks and threads, and the journal it writes resumes on any number of ranks.
//
// Messages (bytes): a worker's report, [kind u8][wants_more u8][run u64][episodes u64][payload], with kind
// nothing / result (payload: encode(i) as JSON text) / cancelled / failed (payload: the error's text) /
// done (the rank's threads have ended); the root's answer to a report that wants more, [run u64], where
// UINT64_MAX means no more runs.

#include <cstddef>
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "sweep/sweep_control.hpp"

namespace peg3d::sweep {

/// What run_distributed saw.
struct DistributedOutcome {
  std::size_t finished = 0;  ///< on the root: runs of `todo` finished on any rank; elsewhere: on this rank
  bool stopped = false;      ///< this rank's stop check asked to stop
};

/// Runs `todo` (read on the root only; other ranks pass anything) of `runs` over control.group, which must hold
/// several ranks, with `threads` worker threads on this rank (resolve_thread_count). On the root, each run is
/// recorded in control.journal (when there is one) as it arrives, and control.progress counts every rank's
/// episodes and runs.
///
/// Stopping: a rank whose stop check fires asks for no more runs and drops its runs in flight; the root
/// whose stop check fires hands out no more runs and waits for every rank's runs in flight. Failures: the
/// root hands out no more runs once one failed anywhere, and after every rank has finished rethrows the
/// exception of the lowest failing run (a run that failed on another rank becomes a std::runtime_error
/// naming the run, the rank and the error's text). Returns on every rank once the root needs it no more.
DistributedOutcome run_distributed(const std::vector<std::size_t>& todo, int threads, const SweepControl& control,
                                   const SweepRuns& runs);

}  // namespace peg3d::sweep
