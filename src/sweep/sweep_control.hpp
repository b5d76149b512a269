#pragma once
// What every sweep is handed besides its own settings: how it is recorded, stopped and spread over processes
// (SweepControl), and what its runs are, as three functions of a run's index (SweepRuns). A sweep knows
// nothing of what a run computes: it calls run(i), which fills the caller's slot i, and moves the slot
// through the journal and between ranks as the JSON record encode(i) makes and restore(i, record) reads.

#include <cstddef>
#include <functional>

#include <nlohmann/json.hpp>

#include "sweep/parallel_runner.hpp"

namespace peg3d::sweep {

class ProcessGroup;
class ProgressReporter;
class RunJournal;

/// How a sweep is recorded, stopped and spread over processes; part of every experiment's settings.
struct SweepControl {
  RunJournal* journal = nullptr;  ///< records each finished run; runs it already holds are read back, not rerun
  StopCheck stop;                 ///< polled before each run and between episodes; true stops the sweep
  /// The processes the sweep is spread over (distributed_sweep.hpp); null or of size 1: this process alone.
  /// With several, only the root (rank 0) has a journal.
  ProcessGroup* group = nullptr;
  /// The progress the runs count into. With a group, the other ranks' episode counts are sent to the root
  /// with their runs and added to the root's reporter, which alone prints. Null: none.
  ProgressReporter* progress = nullptr;
};

/// The runs of a sweep, by index. Each must depend on its index only (parallel_runner.hpp), and
/// restore(i, encode(i)) must rebuild slot i exactly, so that a resumed or distributed sweep ends with the
/// slots of a sweep run at once in one process.
struct SweepRuns {
  std::function<void(std::size_t)> run;                               ///< computes run i into slot i
  std::function<nlohmann::json(std::size_t)> encode;                  ///< slot i as a journal record
  std::function<void(std::size_t, const nlohmann::json&)> restore;    ///< fills slot i from a record
};

}  // namespace peg3d::sweep
