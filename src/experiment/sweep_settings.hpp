#pragma once
// What every experiment sweep has, in the manner of OMPL's Benchmark::Request: a root seed, a training budget,
// a number of repeats, the threads, and how the sweep is recorded, stopped and spread over processes. Each
// experiment's settings hold one and add their own fields (the paper's traced repeat, the matchups' policies,
// the league's evaluation seeds).

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "sweep/sweep_control.hpp"
#include "world/arena.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::experiment {

struct SweepSettings {
  std::uint64_t seed = 1;  ///< root seed; every run's seed derives from it
  int episodes = 200;      ///< training episodes per run, >= 0
  /// Runs per cell of the sweep, >= 1: per scenario (and algorithm) in the paper's sweep, the matchups and the
  /// generalization; training runs (seeds) per algorithm in the league.
  int repeats = 20;
  int threads = 0;              ///< worker threads per process, 0: every core of its CPU affinity; results do not depend on it
  sweep::SweepControl control{};  ///< journal, stop request, ranks and progress (none by default)
};

/// What every sweep's journal header starts with: {"experiment", "peg3d" (version and commit), "map_hash" (of the
/// map it trains on), "seed", "episodes"}; each experiment adds what else its results depend on.
nlohmann::json setup_header(const char* experiment, const world::Arena& map, const SweepSettings& settings);

/// The seed of a scenario's repeat: derive_seed(root, {scenario, repeat}), shared by every algorithm and
/// pairing that plays that start, so that they are compared on paired runs.
std::uint64_t run_seed(std::uint64_t root, int scenario, int repeat);

/// Every run of a sweep over scenarios x repeats (run = scenario index * repeats + repeat) with its seed, for
/// run_info.json: [{"run", "scenario", "repeat", "seed"}].
nlohmann::ordered_json scenario_run_seeds(const std::vector<world::Scenario>& scenarios, int repeats,
                                          std::uint64_t root);

}  // namespace peg3d::experiment
