#include "cli_common.hpp"

#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

#include "core/validation.hpp"
#include "experiment/config_overrides.hpp"
#include "world/map_spec.hpp"

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
  app.add_option("--set", o.sets, "override a configuration field: key=value (repeatable)");
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
  const auto input_error = [](const std::string& what) {
    std::fprintf(stderr, "error: %s\n", what.c_str());
    return 2;
  };
  try {
    return body();
  } catch (const world::MapError& e) {
    return input_error(e.what());
  } catch (const InvalidParameter& e) {
    return input_error(e.what());
  } catch (const experiment::ConfigError& e) {
    return input_error(e.what());
  } catch (const InputError& e) {
    return input_error(e.what());
  } catch (const std::invalid_argument& e) {
    return input_error(e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}

std::filesystem::path resolve_input(const std::filesystem::path& p) {
  if (p.empty() || p.is_absolute() || std::filesystem::exists(p)) return p;
  const std::filesystem::path in_source = std::filesystem::path(PEG3D_SOURCE_DIR) / p;
  return std::filesystem::exists(in_source) ? in_source : p;
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
  const std::filesystem::path path = std::filesystem::path(PEG3D_SOURCE_DIR) / "tools" / script;
  const std::string cmd = fmt::format("/usr/bin/python3 '{}' '{}'", path.string(), dir.string());
  const int rc = std::system(cmd.c_str());
  if (rc != 0) {
    std::fprintf(stderr, "warning: %s failed (status %d); the figures were not drawn\n", script.c_str(), rc);
    return false;
  }
  return true;
}

}  // namespace peg3d::cli
