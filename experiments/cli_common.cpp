#include "cli_common.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

#include "world/map_spec.hpp"

extern char** environ;

namespace peg3d::cli {

void add_sweep_options(CLI::App& app, SweepOptions& o) {
  app.add_option("--map", o.map, "map file (YAML, docs/maps.md)")->capture_default_str();
  app.add_option("--out", o.out, "output folder")->capture_default_str();
  app.add_option("--seed", o.seed, "root seed; every run's seed derives from it")->capture_default_str();
  app.add_option("--episodes", o.episodes, "training episodes per run")->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("--repeats", o.repeats, "runs per scenario and algorithm")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--threads", o.threads, "worker threads (0: all cores); results do not depend on it")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--set", o.sets, "override a configuration field: key=value (repeatable; --list-config shows them)");
  app.add_flag("--no-cache", o.no_cache, "rebuild the world instead of using the on-disk cache");
  app.add_flag("--plain-progress", o.plain_progress, "progress as plain lines even on a terminal");
}

int guarded_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("error: ") + e.what() + "\nRun with --help for more information.\n";
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (...) {
    std::fprintf(stderr, "error: an unexpected failure\n");
    return 1;
  }
}

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

}  // namespace peg3d::cli
