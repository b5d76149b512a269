#include "cli_common.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string_view>
#include <tuple>

#include <fmt/format.h>
#include <fnmatch.h>

#include "mpi_process_group.hpp"
#include "view/viewer_html.hpp"

#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"

extern char** environ;

namespace peg3d::cli {
namespace {

// The signal that asked the sweep to stop; written by the handler, so a lock-free atomic (async-signal-safe).
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

void on_stop_signal(int sig) { g_stop_signal.store(sig, std::memory_order_relaxed); }

/// An argument as a POSIX shell reads it back: as is when it holds only safe characters, else single-quoted.
std::string shell_quoted(const std::string& arg) {
  bool safe = !arg.empty();
  for (const char c : arg) {
    safe = safe && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    std::string_view("_-./=:,+@%").find(c) != std::string_view::npos);
  }
  if (safe) return arg;
  std::string quoted = "'";
  for (const char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// The command line that resumes this sweep: argv as given, plus --resume unless it is there already.
std::string resume_command(int argc, char** argv) {
  std::string command;
  bool has_resume = false;
  for (int i = 0; i < argc; ++i) {
    has_resume = has_resume || std::string_view(argv[i]) == "--resume";
    command += (i == 0 ? "" : " ") + shell_quoted(argv[i]);
  }
  return has_resume ? command : command + " --resume";
}

}  // namespace

struct StopOnSignals::Saved {
  struct sigaction interrupt {};
  struct sigaction terminate {};
  bool interrupt_set = false, terminate_set = false;
};

StopOnSignals::StopOnSignals() : saved_(std::make_unique<Saved>()) {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  for (auto [sig, old, set] : {std::tuple{SIGINT, &saved_->interrupt, &saved_->interrupt_set},
                                  std::tuple{SIGTERM, &saved_->terminate, &saved_->terminate_set}}) {
    if (sigaction(sig, nullptr, old) != 0 || old->sa_handler == SIG_IGN) continue;  // ignored: stays so
    *set = sigaction(sig, &action, nullptr) == 0;
  }
}

StopOnSignals::~StopOnSignals() {
  if (saved_->interrupt_set) sigaction(SIGINT, &saved_->interrupt, nullptr);
  if (saved_->terminate_set) sigaction(SIGTERM, &saved_->terminate, nullptr);
}

sweep::StopCheck stop_check() {
  return [] { return g_stop_signal.load(std::memory_order_relaxed) != 0; };
}

int stop_signal() { return g_stop_signal.load(std::memory_order_relaxed); }

std::unique_ptr<sweep::RunJournal> open_journal(const SweepOptions& o, std::size_t runs, const nlohmann::json& setup) {
  const std::filesystem::path file = o.out / sweep::kJournalFileName;
  std::error_code ec;
  const bool exists = std::filesystem::exists(std::filesystem::symlink_status(file, ec));
  if (o.resume) {
    if (!exists) {
      throw InputError(fmt::format("--resume: there is no journal {} to resume (a sweep that finished removes its "
                                   "journal; run without --resume to start one)",
                                   file.string()));
    }
    auto journal = sweep::RunJournal::resume(file, runs, setup);
    if (journal->dropped_torn_line()) {
      std::fprintf(stderr, "note: dropped the torn last line of %s (a run being written when the sweep died)\n",
                   file.string().c_str());
    }
    std::fprintf(stderr, "resuming: %zu of %zu runs are in %s; running the other %zu\n", journal->recorded(), runs,
                 file.string().c_str(), runs - journal->recorded());
    return journal;
  }
  if (exists) {
    throw InputError(fmt::format("--out {}: holds {}, the journal of an unfinished sweep: pass --resume to finish "
                                 "it, or choose another --out",
                                 o.out.string(), file.filename().string()));
  }
  prepare_output_dir(o.out);
  return sweep::RunJournal::create(file, runs, setup);
}

void add_sweep_options(CLI::App& app, SweepOptions& o) {
  app.add_option("--map", o.map, "map file (YAML, docs/maps.md)")->capture_default_str();
  app.add_option("--out", o.out, "output folder")->capture_default_str();
  app.add_option("--seed", o.sweep.seed, "root seed; every run's seed derives from it")->capture_default_str();
  app.add_option("--episodes", o.sweep.episodes, "training episodes per run")->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("--repeats", o.sweep.repeats, "runs per scenario and algorithm")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--threads", o.sweep.threads, "worker threads (0: every core this process may run on; under MPI, per rank); results do not depend on it")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--set", o.sets, "override a configuration field: key=value (repeatable; --list-config shows them)");
  app.add_flag("--no-cache", o.no_cache, "rebuild the world instead of using the on-disk cache");
  app.add_flag("--plain-progress", o.plain_progress, "progress as plain lines even on a terminal");
  app.add_flag("--resume", o.resume,
               "finish the interrupted sweep whose journal (runs.journal) is in --out: same flags, only the missing "
               "runs are run");
}

namespace {

// The MPI ranks of an experiment binary (sweep_main), and where the sweep is: failures are settled across
// ranks by agreement before it, by ending every rank during it; after it only the root works.
std::unique_ptr<sweep::ProcessGroup> g_group;
enum class SweepPhase { kSetUp, kSweep, kAfter };
SweepPhase g_phase = SweepPhase::kSetUp;

bool several_ranks() { return g_group && g_group->size() > 1; }

// Thrown by begin_sweep on the ranks whose set-up succeeded when another's failed: end with its status.
struct PeerFailed {
  int status;
};

// Prints a failure's message and returns its status; with several ranks, settles it first (sweep_main).
int settle(int status, const std::string& message, bool root_only = false) {
  if (several_ranks() && g_phase == SweepPhase::kSetUp) {
    const sweep::ProcessGroup::Failure f = g_group->agree(status);
    if (f.rank == g_group->rank()) std::fputs(message.c_str(), stderr);
    return f.status;
  }
  if (!several_ranks() || !root_only || g_group->is_root()) std::fputs(message.c_str(), stderr);
  return status;
}

int guarded(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("error: ") + e.what() + "\nRun with --help for more information.\n";
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Every rank parses the same flags: the root alone prints.
    std::ostringstream out, err;
    const int status = app.exit(e, out, err) == 0 ? 0 : 2;
    if (!several_ranks() || g_group->is_root()) std::fputs(out.str().c_str(), stdout), std::fputs(err.str().c_str(), stderr);
    return status;
  }
  try {
    return body();
  } catch (const PeerFailed& p) {
    return p.status;
  } catch (const sweep::SweepInterrupted& e) {
    const int sig = stop_signal();
    const char* name = sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a stop request";
    const std::string message =
        e.journal().empty()
            ? fmt::format("interrupted by {}: {} of {} runs had finished; no result files written\n", name, e.kept(),
                          e.total())
            : fmt::format("interrupted by {}: kept {} of {} runs in {}; no result files written\nresume with: {}\n",
                          name, e.kept(), e.total(), e.journal().string(), resume_command(argc, argv)) +
                  (several_ranks() ? "(launched as this sweep was, by mpirun or srun, on any number of ranks)\n" : "");
    return settle(sig > 0 ? 128 + sig : 1, message, /*root_only=*/true);
  } catch (const InputError& e) {
    return settle(2, fmt::format("error: {}\n", e.what()));
  } catch (const std::exception& e) {
    return settle(1, fmt::format("error: {}\n", e.what()));
  } catch (...) {
    return settle(1, "error: an unexpected failure\n");
  }
}

}  // namespace

int guarded_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  return guarded(app, argc, argv, body);
}

int sweep_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  if (launched_as_mpi_ranks()) {
#ifdef PEG3D_HAVE_MPI
    try {
      g_group = join_mpi_ranks(&argc, &argv);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
#else
    if (const int ranks = launched_rank_count(); ranks > 1) {
      std::fprintf(stderr, "error: started as %d MPI ranks, but this peg3d was built without MPI: install "
                           "libopenmpi-dev and rebuild, or run one process with --threads\n", ranks);
      return 2;
    }
#endif
  }
  const int status = guarded(app, argc, argv, body);
  g_group.reset();  // MPI_Finalize, once every rank is done with the others
  return status;
}

sweep::ProcessGroup* process_group() { return g_group.get(); }

bool SweepSession::root() const { return !control.group || control.group->is_root(); }

void SweepSession::complete() {
  if (journal) journal->remove();
}

void SweepSession::discard() {
  if (!journal || !started_journal) return;
  journal->remove();
  std::error_code ec;
  if (!made_out.empty() && std::filesystem::is_empty(made_out, ec)) std::filesystem::remove(made_out, ec);
}

SweepSession open_sweep(const SweepOptions& o, std::size_t runs, std::size_t episodes_per_run,
                        const nlohmann::json& setup) {
  SweepSession s;
  s.control.group = g_group.get();
  s.control.stop = stop_check();
  if (s.root()) {
    std::error_code ec;
    if (!std::filesystem::exists(o.out, ec)) s.made_out = o.out;
    s.started_journal = !o.resume;
    s.journal = open_journal(o, runs, setup);
    const std::size_t left = runs - s.journal->recorded();
    s.progress = std::make_unique<sweep::ProgressReporter>(left, left * episodes_per_run, stderr, o.plain_progress);
  } else {
    s.progress = std::make_unique<sweep::ProgressReporter>(0, 0, nullptr);
  }
  s.control.journal = s.journal.get();
  s.control.progress = s.progress.get();
  return s;
}

namespace detail {

void begin_sweep() {
  if (several_ranks()) {
    const sweep::ProcessGroup::Failure f = g_group->agree(0);
    if (f.rank >= 0) throw PeerFailed{f.status};
  }
  g_phase = SweepPhase::kSweep;
}

void end_sweep() { g_phase = SweepPhase::kAfter; }

void fail_in_sweep(const std::exception& e) {
  g_phase = SweepPhase::kAfter;
  if (!several_ranks()) return;
  // Other ranks may be waiting on this one: end them all.
  const int status = dynamic_cast<const InputError*>(&e) ? 2 : 1;
  std::fprintf(stderr, "error: rank %d: %s\n", g_group->rank(), e.what());
  std::fflush(stderr);
  g_group->abort(status);
}

}  // namespace detail

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("PEG3D_DATA_DIR"); env != nullptr && *env != '\0') return env;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "share/peg3d";
  return (exe.parent_path().parent_path() / "share" / "peg3d").lexically_normal();
}

std::filesystem::path resolve_input(const std::filesystem::path& p) {
  std::error_code ec;
  if (p.empty() || p.is_absolute() || std::filesystem::exists(p, ec)) return p;
  const std::filesystem::path shipped = data_dir() / p;
  return std::filesystem::exists(shipped, ec) ? shipped : p;
}

std::shared_ptr<const world::Arena> load_arena(const std::filesystem::path& map, bool use_cache) {
  const world::MapSpec spec = world::load_map(resolve_input(map));
  world::BuildOptions options;
  if (use_cache) options.cache_dir = world::default_cache_dir();
  return world::Arena::build(spec, options);
}

void prepare_output_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw InputError(fmt::format("--out {}: exists and is not a folder", dir.string()));
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot create: {}", dir.string(), ec.message()));
}

bool run_plot_script(const std::string& script, const std::filesystem::path& dir) {
  const std::string python = "/usr/bin/python3";
  const std::string path = (data_dir() / "tools" / script).string();
  const std::string folder = dir.string();
  std::vector<char*> argv{const_cast<char*>(python.c_str()), const_cast<char*>(path.c_str()),
                          const_cast<char*>(folder.c_str()), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ);
  int status = 0;
  if (spawned != 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "warning: %s failed (%s); the figures were not drawn\n", script.c_str(),
                 spawned != 0 ? "cannot start /usr/bin/python3" : fmt::format("status {}", status).c_str());
    return false;
  }
  return true;
}

void add_html_option(CLI::App& app, std::vector<std::string>& patterns, const std::string& keys) {
  app.add_option("--html", patterns,
                 "write a replay viewer file (one HTML page, docs/viewer.md) for each run whose key matches one of "
                 "these shell patterns (" + keys + "; 'all': every run)")
      ->delimiter(',');
}

bool key_chosen(const std::vector<std::string>& patterns, const std::string& key) {
  for (const auto& p : patterns) {
    if (p == "all" || ::fnmatch(p.c_str(), key.c_str(), 0) == 0) return true;
  }
  return false;
}

std::uintmax_t write_viewer(const std::filesystem::path& file, const view::ReplayScene& scene, const game::Sim& sim,
                            const game::Trace& trace, const view::ReplayInfo& info) {
  static const view::ViewerAssets assets = view::ViewerAssets::load(data_dir() / "assets" / "viewer");
  view::write_viewer_html(file, assets, view::replay_json(scene, sim, trace, info), info.title);
  return std::filesystem::file_size(file);
}

std::uintmax_t write_case_viewer(const std::filesystem::path& file, const regress::CollisionCase& c,
                                 const regress::CasePlay& play, const std::string& title,
                                 const view::ReplaySettings& settings) {
  return write_viewer(file, view::ReplayScene(play.sim.arena(), settings), play.sim, play.trace,
                      {title.empty() ? "case " + c.name : title,
                       fmt::format("{} on {}; {} collision(s), {} at {:.2f} s", c.file.string(), c.map.filename().string(),
                                   play.log.events.size(), play.log.outcome, play.log.time)});
}

void report_viewers(const std::vector<std::string>& files, const std::vector<std::string>& patterns) {
  for (const auto& f : files) std::printf("replay viewer: %s\n", f.c_str());
  if (files.empty() && !patterns.empty()) {
    std::fprintf(stderr, "warning: --html chose no run (see --help for the keys runs have)\n");
  }
}

}  // namespace peg3d::cli
