#pragma once
// The journal of a sweep: every finished run is appended to `<out>/runs.journal` as it finishes, flushed to
// the disk, so a crash or an interruption loses only the runs in flight, and `--resume` reruns only the
// missing ones. Runs depend only on their index (parallel_runner.hpp), so final files rebuilt from the
// journal, sorted by run index, are byte-identical to those of an uninterrupted sweep. What a record holds is
// the experiment's business (its codecs, results/codecs.hpp); the journal keeps JSON values by run index.
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


namespace peg3d::sweep {

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

/// Where two JSON values first differ (keys in sorted order, then list elements in order).
struct JsonDifference {
  std::string field;         ///< dotted path, "algorithms[1].config.dt"; empty when they differ at the top
  nlohmann::json a, b;       ///< the values there (null when one side lacks the field)
};
std::optional<JsonDifference> first_difference(const nlohmann::json& a, const nlohmann::json& b);

}  // namespace peg3d::sweep
