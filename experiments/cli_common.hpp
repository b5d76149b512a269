#pragma once
// What the peg3d programs share: the common flags of the experiment binaries, where the data files (maps,
// meshes, plot scripts) are, loading a map into an Arena, and turning errors into exit codes: 2 for
// exactly the errors caused by input (peg3d::InputError: flags, maps, meshes, configurations, policy files),
// 1 for anything else.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/error.hpp"
#include "world/arena.hpp"

namespace peg3d::cli {

struct SweepOptions {
  std::filesystem::path map;
  std::filesystem::path out;
  std::uint64_t seed = 1;
  int episodes = 200;
  int repeats = 20;
  int threads = 0;
  std::vector<std::string> sets;
  bool no_cache = false;
  bool plain_progress = false;
};

/// --map --out --seed --episodes --repeats --threads --set --no-cache --plain-progress
void add_sweep_options(CLI::App& app, SweepOptions& o);

/// Parses argv and runs body. Prints "error: ..." on stderr and returns 2 for bad flags and every
/// peg3d::InputError, 1 for any other failure; otherwise the body's status.
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

/// Runs `/usr/bin/python3 <data_dir>/tools/<script> <dir>` (an argument vector, no shell); false (with a
/// warning) when it fails.
bool run_plot_script(const std::string& script, const std::filesystem::path& dir);

}  // namespace peg3d::cli
