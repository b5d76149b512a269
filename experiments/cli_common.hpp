#pragma once
// What the experiment binaries share: the common flags, loading a map into an Arena, and turning errors into
// exit codes (2 for bad input: flags, maps, configurations, policy files; 1 for failures while running).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "world/arena.hpp"

namespace peg3d::cli {

/// Bad input found by an experiment binary itself (exit status 2).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

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

/// Parses argv and runs body, printing "error: ..." on stderr and returning 2 for bad input, 1 for other
/// failures. The body returns the exit status.
int guarded_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

/// A map path as given, or else relative to the source tree (so defaults work from any folder).
std::filesystem::path resolve_input(const std::filesystem::path& p);

/// Loads and builds a map, through the on-disk cache unless disabled.
std::shared_ptr<const world::Arena> load_arena(const std::filesystem::path& map, bool use_cache);

/// Creates the output folder (and parents). Throws InputError when it exists as a file.
void prepare_output_dir(const std::filesystem::path& dir);

/// Runs tools/<script> with Debian's /usr/bin/python3 on `dir`; false (with a warning) when it fails.
bool run_plot_script(const std::string& script, const std::filesystem::path& dir);

}  // namespace peg3d::cli
