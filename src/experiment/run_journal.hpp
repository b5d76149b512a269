#pragma once
// The journal of a sweep: every finished run is appended to `<out>/runs.journal` as it finishes, flushed to
// the disk, so a crash or an interruption loses only the runs in flight, and `--resume` reruns only the
// missing ones. Runs depend only on their index (parallel_runner.hpp), so final files rebuilt from the
// journal, sorted by run index, are byte-identical to those of an uninterrupted sweep.
//
// Format (JSON lines; docs/results.md):
//   line 1   {"format": "peg3d-journal", "version": 1, "runs": M, "setup": {...}}
//   then     {"run": i, "data": {...}}   one line per finished run, in the order the runs finished
// `setup` is everything the results depend on (the experiment, the peg3d version, the configuration, the
// seed, the maps' content hashes, the budgets); a journal is only resumed by a sweep with the same setup.
// The last line may be torn (a crash mid-write): it is dropped. Any other bad line is an InputError.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/parallel_runner.hpp"
#include "game/episode.hpp"
#include "game/lineup.hpp"

namespace peg3d::experiment {

class ProcessGroup;
class ProgressReporter;

inline constexpr const char* kJournalFormat = "peg3d-journal";
inline constexpr int kJournalVersion = 1;
/// The journal's name in an experiment's output folder.
inline constexpr const char* kJournalFileName = "runs.journal";

class RunJournal {
 public:
  /// Starts a journal for a sweep of `runs` runs: writes the header line (atomically). Throws InputError
  /// when `file` exists already (an interrupted sweep: resume it, or choose another folder; never mixed).
  static std::unique_ptr<RunJournal> create(const std::filesystem::path& file, std::size_t runs,
                                            const nlohmann::json& setup);
  /// Opens an existing journal to finish its sweep, reading back the runs it holds. Throws InputError naming
  /// the file, line and field when it is missing, is not a journal, was written for another setup or run
  /// count (naming the first field that differs), or holds a bad line other than a torn last one, which is
  /// dropped (and cut from the file, so appends start on a fresh line).
  static std::unique_ptr<RunJournal> resume(const std::filesystem::path& file, std::size_t runs,
                                            const nlohmann::json& setup);
  ~RunJournal();

  RunJournal(const RunJournal&) = delete;
  RunJournal& operator=(const RunJournal&) = delete;

  const std::filesystem::path& file() const noexcept { return file_; }
  /// Runs the sweep plans.
  std::size_t runs() const noexcept { return runs_; }
  /// Runs recorded: read back when opened plus appended since. Thread-safe.
  std::size_t recorded() const;
  /// Whether run `run` is recorded. Thread-safe.
  bool has(std::size_t run) const;
  /// Whether resume() dropped a torn last line.
  bool dropped_torn_line() const noexcept { return dropped_torn_line_; }

  /// Hands the data read back for `run` (recorded before the journal was opened) to `decode`. Errors of
  /// decode (a missing or mistyped field, an InputError) become an InputError naming the file, the run's
  /// line and "run <i>". Throws std::logic_error when the run was not read back.
  void restore(std::size_t run, const std::function<void(const nlohmann::json&)>& decode) const;
  /// Frees the data read back (after every restore).
  void release_restored();

  /// Appends a finished run as one line, written with one call and synced to the disk before returning.
  /// Thread-safe. Throws std::logic_error for a run out of range or already recorded, std::runtime_error
  /// (naming the file) when the write fails.
  void record(std::size_t run, const nlohmann::json& data);

  /// Deletes the journal: the sweep is complete and its final files are written.
  void remove();

 private:
  RunJournal(std::filesystem::path file, std::size_t runs);
  void open_for_append();

  struct Restored {
    int line = 0;
    nlohmann::json data;
  };

  std::filesystem::path file_;
  std::size_t runs_ = 0;
  int fd_ = -1;
  bool dropped_torn_line_ = false;
  mutable std::mutex mutex_;  // guards done_, recorded_ and writes to fd_
  std::vector<char> done_;
  std::size_t recorded_ = 0;
  std::map<std::size_t, Restored> restored_;
};

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

/// Runs 0..count-1 as run_indexed does (same threads and determinism), through `control`:
/// - the runs the journal holds are handed to restore(i, data), in index order, before any run starts;
/// - every other run is computed by run(i) and, once it returns, encode(i) is appended to the journal;
/// - on a stop request no further run starts, runs in flight give up (run throws RunCancelled) and are
///   dropped, and SweepInterrupted is thrown once the threads are joined, unless every run finished anyway.
/// encode is not called without a journal. Other exceptions of run propagate as in run_indexed.
///
/// With a group of several processes (control.group), every rank calls this with the same arguments but
/// `threads`: the runs are spread over the ranks as in run_distributed (distributed_sweep.hpp), and on the
/// root every run ends up in its slot exactly as in a single-process sweep, computed there or restored from
/// another rank's encode(i). The other ranks return once the root needs them no more; their slots are not
/// all filled.
void run_journaled(std::size_t count, int threads, const SweepControl& control,
                   const std::function<void(std::size_t)>& run,
                   const std::function<nlohmann::json(std::size_t)>& encode,
                   const std::function<void(std::size_t, const nlohmann::json&)>& restore);

/// Where two JSON values first differ (keys in sorted order, then list elements in order).
struct JsonDifference {
  std::string field;         ///< dotted path, "algorithms[1].config.dt"; empty when they differ at the top
  nlohmann::json a, b;       ///< the values there (null when one side lacks the field)
};
std::optional<JsonDifference> first_difference(const nlohmann::json& a, const nlohmann::json& b);

// Codecs of what runs produce, exact to the bit for finite doubles (shortest round-trip text) and keeping
// NaN and infinities (as the strings "nan", "-nan", "inf", "-inf"). Decoders throw nlohmann::json
// exceptions or std::invalid_argument on malformed input (RunJournal::restore turns them into InputErrors).

nlohmann::json number_to_json(double v);
double number_from_json(const nlohmann::json& j);

nlohmann::json episode_to_json(const game::EpisodeResult& e);
game::EpisodeResult episode_from_json(const nlohmann::json& j);
nlohmann::json episodes_to_json(const std::vector<game::EpisodeResult>& episodes);
std::vector<game::EpisodeResult> episodes_from_json(const nlohmann::json& j);

nlohmann::json agent_summary_to_json(const game::AgentSummary& a);
game::AgentSummary agent_summary_from_json(const nlohmann::json& j);

/// Every frame, collision and capture of a trace.
nlohmann::json trace_to_json(const game::Trace& t);
game::Trace trace_from_json(const nlohmann::json& j);

/// A role's trained models (policy documents, game/policy_io.hpp) and which one each agent plays. Decoding
/// rebuilds each model; a model of the other role is an error.
nlohmann::json role_models_to_json(const game::RoleModels& m);
game::RoleModels role_models_from_json(const nlohmann::json& j, game::Role role);

}  // namespace peg3d::experiment
