#include "sweep/sweep_driver.hpp"

#include <atomic>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "sweep/distributed_sweep.hpp"
#include "sweep/process_group.hpp"
#include "sweep/run_journal.hpp"

namespace peg3d::sweep {
namespace {

/// The runs `journal` does not hold, in index order; the ones it holds are restored into their slots first.
std::vector<std::size_t> restore_journaled(std::size_t count, RunJournal* journal, const SweepRuns& runs) {
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < count; ++i) {
    if (journal && journal->has(i)) {
      journal->restore(i, [&](const nlohmann::json& data) { runs.restore(i, data); });
    } else {
      todo.push_back(i);
    }
  }
  if (journal) journal->release_restored();
  return todo;
}

SweepInterrupted interrupted(std::size_t kept, std::size_t count, const RunJournal* journal) {
  return {journal ? journal->recorded() : kept, count, journal ? journal->file() : std::filesystem::path()};
}

}  // namespace

SweepInterrupted::SweepInterrupted(std::size_t kept, std::size_t total, std::filesystem::path journal)
    : std::runtime_error(fmt::format("sweep interrupted: {} of {} runs finished", kept, total)),
      kept_(kept),
      total_(total),
      journal_(std::move(journal)) {}

void run_sweep(std::size_t count, int threads, const SweepControl& control, const SweepRuns& runs) {
  RunJournal* journal = control.journal;
  const bool distributed = control.group && control.group->size() > 1;
  if (journal && distributed && !control.group->is_root()) {
    throw std::logic_error("run_sweep: only the root of a process group keeps the journal");
  }
  if (journal && journal->runs() != count) {
    throw std::logic_error(fmt::format("run_sweep: the journal plans {} runs, the sweep {}", journal->runs(), count));
  }
  const std::vector<std::size_t> todo = restore_journaled(count, journal, runs);

  if (distributed) {
    const DistributedOutcome outcome = run_distributed(todo, threads, control, runs);
    if (!control.group->is_root()) {
      if (outcome.stopped) throw SweepInterrupted(outcome.finished, count, {});
      return;
    }
    if (outcome.finished < todo.size()) throw interrupted(count - todo.size() + outcome.finished, count, journal);
    return;
  }

  std::atomic<std::size_t> finished{0};
  run_indexed(
      todo.size(), threads,
      [&](std::size_t k) {
        const std::size_t i = todo[k];
        try {
          runs.run(i);
        } catch (const RunCancelled&) {
          return;  // dropped: it reruns on resume
        }
        if (journal) journal->record(i, runs.encode(i));
        finished.fetch_add(1, std::memory_order_relaxed);
      },
      control.stop);
  if (finished.load() < todo.size()) throw interrupted(finished.load(), count, journal);
}

}  // namespace peg3d::sweep
