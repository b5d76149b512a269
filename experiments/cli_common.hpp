#pragma once
// What the peg3d programs share: the common flags of the experiment binaries, where the data files (maps,
// meshes, plot scripts) are, loading a map into an Arena, and turning errors into exit codes: 2 for
// exactly the errors caused by input (peg3d::InputError: flags, maps, meshes, configurations, policy files,
// journals), 1 for anything else, 128 + the signal (130 for SIGINT, 143 for SIGTERM) for a sweep stopped by
// one. The signal handlers live here, not in the library: they only set a flag the sweeps poll.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/error.hpp"
#include "experiment/sweep_settings.hpp"
#include "game/episode.hpp"
#include "game/sim.hpp"
#include "regress/collision_case.hpp"
#include "sweep/process_group.hpp"
#include "sweep/progress_reporter.hpp"
#include "sweep/run_journal.hpp"
#include "sweep/sweep_driver.hpp"
#include "view/replay.hpp"
#include "world/arena.hpp"

namespace peg3d::cli {

struct SweepOptions {
  std::filesystem::path map;
  std::filesystem::path out;
  /// --seed, --episodes, --repeats, --threads; the control is the session's (open_sweep).
  experiment::SweepSettings sweep;
  std::vector<std::string> sets;
  bool no_cache = false;
  bool plain_progress = false;
  bool resume = false;  ///< finish the sweep whose journal is in `out`
};

/// --map --out --seed --episodes --repeats --threads --set --no-cache --plain-progress --resume
void add_sweep_options(CLI::App& app, SweepOptions& o);

/// Parses argv and runs body. Prints "error: ..." on stderr and returns 2 for bad flags and every
/// peg3d::InputError, 1 for any other failure; otherwise the body's status. A sweep stopped by a signal
/// (sweep::SweepInterrupted) prints what was kept and the command that resumes it (argv plus
/// --resume), and returns 128 + the signal.
int guarded_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

/// The folder of peg3d's data files: $PEG3D_DATA_DIR when set, else share/peg3d beside the executable's
/// folder (build/share/peg3d in a build tree, <prefix>/share/peg3d when installed). Holds maps/, assets/
/// and tools/.
std::filesystem::path data_dir();

/// A path as given when it exists (or is absolute), else the same relative path under data_dir(), so that
/// `--map maps/paper.yaml` works from any folder.
std::filesystem::path resolve_input(const std::filesystem::path& p);

/// Loads and builds a map, through the on-disk cache unless disabled.
std::shared_ptr<const world::Arena> load_arena(const std::filesystem::path& map, bool use_cache);

/// Creates the output folder (and parents). Throws InputError when it exists as a file or cannot be made.
void prepare_output_dir(const std::filesystem::path& dir);

/// The sweep's journal, `out/runs.journal` (sweep/run_journal.hpp). Without --resume: creates `out`
/// and a new journal; an existing journal is an InputError (pass --resume, or choose another --out: runs of
/// two sweeps are never mixed). With --resume: reads the journal back (InputError when there is none or it
/// belongs to another setup) and says on stderr how many runs are done.
std::unique_ptr<sweep::RunJournal> open_journal(const SweepOptions& o, std::size_t runs, const nlohmann::json& setup);

/// The stop request the sweeps poll: true once SIGINT or SIGTERM arrived while a StopOnSignals was alive.
sweep::StopCheck stop_check();
/// The signal that asked to stop (SIGINT, SIGTERM); 0 when none did.
int stop_signal();

/// While alive, SIGINT and SIGTERM ask the sweep to stop (stop_check) instead of ending the program at once.
/// The handler only stores the signal. It is installed with SA_RESETHAND, so a second Ctrl-C ends the
/// program as usual (the journal is safe: a torn last line is dropped on resume). A signal ignored before
/// (a background job of a script) stays ignored. The previous handlers come back on destruction.
class StopOnSignals {
 public:
  StopOnSignals();
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  struct Saved;
  std::unique_ptr<Saved> saved_;
};

/// guarded_main for the experiment binaries, which also run as MPI ranks (README, "Sweeps on a cluster"). When
/// an MPI launcher (mpirun, srun) started the program and peg3d was built with MPI, it first joins the ranks
/// (process_group()), and failures are settled across them so that none waits forever:
/// - before the sweep (flags, maps, configurations, the journal): every rank ends with the status of the
///   lowest failing rank, which alone prints its error;
/// - during the sweep: the failing rank prints its error and ends every rank (MPI_Abort);
/// - after it only the root works: it writes the result files; the other ranks return 0 (or 128 + the signal
///   that stopped them), silently.
/// Started by a launcher as several ranks, a build without MPI refuses to run (status 2) rather than run
/// the whole sweep once per rank.
int sweep_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

/// The ranks this experiment binary runs on; null when it runs alone.
sweep::ProcessGroup* process_group();

/// A sweep as the experiment binaries run it.
struct SweepSession {
  std::unique_ptr<sweep::RunJournal> journal;         ///< on the root only (open_journal)
  std::unique_ptr<sweep::ProgressReporter> progress;  ///< prints on the root, only counts elsewhere
  sweep::SweepControl control;                        ///< the journal, the stop signals, the ranks, progress

  /// Whether this process writes the results: it runs alone or is rank 0.
  bool root() const;
  /// Removes the journal: every result file is written.
  void complete();
  /// After an input error during the runs (a policy's command refused by step(), say): removes a journal this
  /// process started, and the output folder when open_journal made it and nothing else is in it, so that a
  /// sweep that failed on its input leaves nothing behind. A resumed journal stays: its runs are still good.
  void discard();

  bool started_journal = false;  ///< the journal is new (not --resume)
  std::filesystem::path made_out;  ///< the output folder open_sweep made (empty: it existed)
};

/// Opens a sweep of `runs` runs of `episodes_per_run` episodes each: on the root the journal (open_journal)
/// and a progress line on stderr; on the other ranks neither touches the disk nor prints.
SweepSession open_sweep(const SweepOptions& o, std::size_t runs, std::size_t episodes_per_run,
                        const nlohmann::json& setup);

namespace detail {
void begin_sweep();
void end_sweep();
void fail_in_sweep(const std::exception& e);
}  // namespace detail

/// Runs a sweep with SIGINT and SIGTERM turned into stop requests, then closes the progress line, also when
/// the sweep was interrupted (SweepInterrupted goes on to sweep_main). With several ranks, it first agrees
/// with them that every set-up succeeded, and a failure during the sweep ends every rank (see sweep_main).
template <class Sweep>
auto run_stoppable(SweepSession& session, Sweep&& sweep) {
  const StopOnSignals signals;
  detail::begin_sweep();
  try {
    auto result = sweep();
    detail::end_sweep();
    session.progress->finish();
    return result;
  } catch (const sweep::SweepInterrupted&) {
    detail::end_sweep();
    session.progress->finish();
    throw;
  } catch (const InputError& e) {
    session.discard();  // on the root, which keeps the journal; a rank failing elsewhere ends them all
    detail::fail_in_sweep(e);  // with several ranks, does not return
    throw;
  } catch (const std::exception& e) {
    detail::fail_in_sweep(e);  // with several ranks, does not return
    throw;
  }
}

/// --html PATTERN...: the runs to write viewer files for (docs/viewer.md). Patterns are shell globs matched
/// against a run's key (peg-paper: SCENARIO_ALGORITHM); "all" chooses every run.
void add_html_option(CLI::App& app, std::vector<std::string>& patterns, const std::string& keys);

/// Whether `key` matches one of the shell patterns (--html, --save-maps); "all" matches every key.
bool key_chosen(const std::vector<std::string>& patterns, const std::string& key);

/// Writes the viewer file of one recorded episode (the viewer's files are read from
/// data_dir()/assets/viewer once) and returns its size in bytes.
std::uintmax_t write_viewer(const std::filesystem::path& file, const view::ReplayScene& scene, const game::Sim& sim,
                            const game::Trace& trace, const view::ReplayInfo& info);

/// Writes the viewer file of a played collision-regression case (title: "case NAME" unless given); returns
/// its size in bytes.
std::uintmax_t write_case_viewer(const std::filesystem::path& file, const regress::CollisionCase& c,
                                 const regress::CasePlay& play, const std::string& title = "",
                                 const view::ReplaySettings& settings = {});

/// Prints "replay viewer: FILE" for each file written; a warning on stderr when --html chose no run.
void report_viewers(const std::vector<std::string>& files, const std::vector<std::string>& patterns);

/// Runs `/usr/bin/python3 <data_dir>/tools/<script> <dir>` (an argument vector, no shell); false (with a
/// warning) when it fails.
bool run_plot_script(const std::string& script, const std::filesystem::path& dir);

}  // namespace peg3d::cli
