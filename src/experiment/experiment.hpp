#pragma once
// What an experiment is, for the one runner every experiment binary uses: a fixed set of independent runs
// (running one, encoding it for the journal and the MPI ranks, restoring it from a record), what it does once
// every run is in (the league plays its games), and what it gives back: result files, the maps and seeds of
// run_info.json, recorded episodes for viewer files, and a report for stdout. The paper's sweep, the matchups,
// the generalization and the league are the four; docs/architecture.md shows how to add a fifth.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "game/episode.hpp"
#include "game/sim.hpp"
#include "sweep/sweep_control.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

/// How a sweep went, for experiments that report it (the paper's timing.json).
struct SweepTiming {
  double build_seconds = 0;  ///< from the program's start to the first run: maps, Sims, the journal (s)
  double run_seconds = 0;    ///< the runs, and finish() (s)
  int threads = 0;           ///< --threads as given (0: every core)
  int ranks = 1;             ///< MPI ranks the runs were spread over
};

/// One episode recorded step by step, which a viewer file can replay.
struct RecordedEpisode {
  std::string key;                    ///< the file's stem, matched by --html patterns (e.g. S1_peg3d)
  const game::Sim* sim = nullptr;     ///< the Sim that played it: its arena and agents are drawn
  const game::Trace* trace = nullptr;
  std::string title, subtitle;
};

/// An experiment: runs 0..run_count()-1, each depending on its index only (sweep/parallel_runner.hpp), so that
/// the results are the same on any thread and rank count and after any resume.
class Experiment {
 public:
  virtual ~Experiment() = default;

  /// run_info.json's "experiment": "paper", "matchup", ...
  virtual std::string kind() const = 0;
  /// Everything the results depend on: the journal's header, which a resumed sweep must match.
  virtual nlohmann::json setup() const = 0;
  virtual std::size_t run_count() const = 0;
  /// Episodes a run plays, for the progress line (an average when runs differ).
  virtual std::size_t episodes_per_run() const = 0;

  /// Before the runs: sizes the slots the runs fill and keeps `control` (stop request, progress) for them.
  virtual void begin(const sweep::SweepControl& control) = 0;
  /// Computes run i into its slot. Called concurrently for distinct i.
  virtual void run_one(std::size_t i) = 0;
  /// Slot i as a journal record, and back: restore(i, encode(i)) rebuilds the slot exactly.
  virtual nlohmann::json encode(std::size_t i) const = 0;
  virtual void restore(std::size_t i, const nlohmann::json& record) = 0;
  /// Once every run is in (computed or restored): gathers the results. `root` says whether this process keeps
  /// them; the other ranks of an MPI sweep return at once.
  virtual void finish(bool root) { (void)root; }

  /// Asks for the episodes whose key `chosen` accepts to be recorded (for viewer files). Experiments that
  /// always record a fixed set (the paper's traced repeat) ignore it.
  virtual void record_episodes(std::function<bool(const std::string&)> chosen) { (void)chosen; }

  /// After finish(true): writes every result file into `out` but run_info.json.
  virtual void write_results(const std::filesystem::path& out, const SweepTiming& timing) const = 0;
  /// run_info.json's maps ("train", "eval forest", ...) and what else it says (seeds and how they derive).
  virtual std::vector<std::pair<std::string, const world::Arena*>> maps() const = 0;
  virtual nlohmann::ordered_json run_info() const = 0;
  /// The recorded episodes (after finish(true)).
  virtual std::vector<RecordedEpisode> recorded() const { return {}; }
  /// The plain-text summary printed at the end.
  virtual std::string report(const SweepTiming& timing) const = 0;
  /// The figure script in tools/ run on `out` after the results are written; empty: none.
  virtual std::string plot_script() const { return {}; }
};

/// How an episode ended, for a viewer's subtitle: "capture at 31.2 s", "timeout at 100 s", ...
std::string ending_of(const game::EpisodeResult& result);

/// Runs every run of `e` on `threads` threads through `control` (sweep/sweep_driver.hpp: the journal's runs
/// restored, the others computed and journaled, spread over control.group's ranks, stopped on request by
/// sweep::SweepInterrupted), then e.finish(root).
void run_experiment(Experiment& e, int threads, const sweep::SweepControl& control, bool root);

}  // namespace peg3d::experiment
