#pragma once
// Progress of a sweep on stderr. On a terminal: one line redrawn in place (bar, runs, episodes/s, time
// left), at most ~10 times a second. In a log file or CI: plain lines, one every 5 s or each 10% of the
// work, so logs stay short. The text comes from pure functions of a ProgressSnapshot and the clock is
// injectable, so both are tested without sleeping.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

namespace peg3d::sweep {

/// Counters of a sweep at one moment.
struct ProgressSnapshot {
  std::size_t total_runs = 0;      ///< runs planned
  std::size_t runs_done = 0;       ///< runs finished, normally <= total_runs
  std::size_t total_episodes = 0;  ///< episodes planned over all runs; 0 when unknown
  std::size_t episodes_done = 0;   ///< episodes finished
  double elapsed_s = 0.0;          ///< s since the reporter started, >= 0
};

/// Share of the work done in [0, 1]: by episodes when total_episodes > 0, else by runs. Nothing planned
/// counts as all done (1).
double progress_fraction(const ProgressSnapshot& s);
/// Episodes per second so far; NaN when no time has passed.
double episodes_per_second(const ProgressSnapshot& s);
/// Seconds left at the average pace so far, elapsed * (1 - f) / f; NaN before any progress, 0 when done.
double eta_seconds(const ProgressSnapshot& s);

/// Compact duration: "42s", "3m05s", "2h03m", "3d04h" (rounded to the unit shown); "--" when NaN,
/// infinite or negative.
std::string format_duration(double seconds);
/// Terminal line without the carriage return:
/// "[#####---------------]  25.0%  10/40 runs  1250/5000 ep  85.3 ep/s  ETA 44s".
std::string format_terminal_line(const ProgressSnapshot& s, int bar_width);
/// Log line: "progress  25.0% | runs 10/40 | episodes 1250/5000 | 85.3 episodes/s | elapsed 14s | ETA 44s".
std::string format_plain_line(const ProgressSnapshot& s);
/// Closing line: "done: 40/40 runs, 5000/5000 episodes in 1m02s (80.6 episodes/s)"; "stopped" instead of
/// "done" when not all planned work was counted (finish() called after a failure).
std::string format_final_line(const ProgressSnapshot& s);

/// How progress is drawn.
enum class ProgressStyle {
  kAuto,      ///< kTerminal when the output is a terminal (isatty), else kPlain
  kTerminal,  ///< one line redrawn with '\r'
  kPlain,     ///< separate lines, for logs
};

/// Settings of a ProgressReporter beyond the totals.
struct ProgressOptions {
  ProgressStyle style = ProgressStyle::kAuto;
  /// Time source; empty means std::chrono::steady_clock::now. Called under the reporter's lock.
  std::function<std::chrono::steady_clock::time_point()> clock = {};
  int bar_width = 20;                                ///< characters inside the bar's brackets, >= 1
  std::chrono::milliseconds terminal_interval{100};  ///< minimum time between redraws (~10 Hz)
  std::chrono::milliseconds plain_interval{5000};    ///< a plain line at least this often while working
};

/// Counts finished episodes and runs from any thread and reports progress on a FILE*. The counters are
/// atomics; printing happens under a mutex, rate-limited as described above.
class ProgressReporter {
 public:
  /// Reports to `out` (stderr by default); force_plain selects plain lines even on a terminal. A null `out`
  /// only counts (a sweep's non-root MPI ranks count episodes for the root, which prints).
  ProgressReporter(std::size_t total_runs, std::size_t total_episodes, std::FILE* out = stderr,
                   bool force_plain = false);
  ProgressReporter(std::size_t total_runs, std::size_t total_episodes, std::FILE* out, ProgressOptions options);
  /// Ends a redrawn line that finish() did not close, so the shell prompt does not land inside it.
  ~ProgressReporter();

  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  /// Counts `count` finished episodes and prints if due. Thread-safe.
  void episode_done(std::size_t count = 1);
  /// Counts one finished run and prints if due. Thread-safe.
  void run_done();
  /// Prints the closing line (format_final_line) once; later calls and later counts print nothing.
  void finish();

  /// The counters now, with the elapsed time from the clock.
  ProgressSnapshot snapshot() const;
  /// Whether the output is drawn as a terminal line (after resolving kAuto).
  bool terminal() const noexcept { return terminal_; }

 private:
  using TimePoint = std::chrono::steady_clock::time_point;

  void maybe_print();
  ProgressSnapshot snapshot_at(TimePoint now) const;
  TimePoint now() const;
  void write(const std::string& text);

  std::size_t total_runs_;
  std::size_t total_episodes_;
  std::FILE* out_;
  ProgressOptions options_;
  bool terminal_;
  TimePoint start_;

  std::atomic<std::size_t> runs_done_{0};
  std::atomic<std::size_t> episodes_done_{0};

  std::mutex print_mutex_;  // guards the fields below and the writes to out_
  TimePoint last_print_;
  int last_decile_ = 0;
  bool line_open_ = false;  // a terminal line was drawn and not yet ended with '\n'
  bool finished_ = false;
};

}  // namespace peg3d::sweep
