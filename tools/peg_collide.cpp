// peg-collide: headless collision-regression tests (docs/collision-tests.md).
//   peg-collide run CASE... [--strict] [--update] [--html DIR]
//                                                   replay cases, compare with their golden logs (and write
//                                                   each case's replay viewer, DIR/CASE.html)
//   peg-collide record CASE...                      write the golden logs (only when asked)
//   peg-collide new --map MAP --motion FILE --out CASE [--agent LABEL] [--scenario NAME] [--set k=v]...
//                                                   make a case from a map and a motion, and record it
// A CASE is a folder holding case.yaml, a NAME.yaml file, or a folder of cases. Exit status: 0 when every case
// matches, 1 when any differs, 2 on bad input (a case, a map, a motion or a golden log that cannot be read).

#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "core/atomic_file.hpp"
#include "regress/collision_case.hpp"
#include "regress/collision_log.hpp"
#include "results/result_files.hpp"
#include "world/map/map_loader.hpp"

using namespace peg3d;

namespace {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, 0, "", "no golden log (record one with: peg-collide record CASE)");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::filesystem::path> expand(const std::vector<std::string>& args) {
  std::vector<std::filesystem::path> out;
  for (const auto& a : args) {
    for (auto& c : regress::find_cases(a)) out.push_back(std::move(c));
  }
  return out;
}

void record(const regress::CollisionCase& c, bool use_cache) {
  const regress::CollisionLog log = regress::run_case(c, use_cache);
  write_file_atomically(c.golden, regress::format_log(log));
  std::printf("recorded %s: %zu collision(s), %zu capture(s), %s at %.2f s -> %s\n", c.name.c_str(), log.events.size(),
              log.captures.size(), log.outcome.c_str(), log.time, c.golden.string().c_str());
}

// The motion file's kind from its name: *.commands or *.waypoints.
std::string motion_kind(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".commands") return "commands";
  if (ext == ".waypoints") return "waypoints";
  throw InputError(file, 0, "", "a motion file is NAME.commands (timed steering) or NAME.waypoints");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"peg-collide: record, replay and compare collision-regression cases"};
  app.require_subcommand(1);
  bool no_cache = false;
  app.add_flag("--no-cache", no_cache, "rebuild worlds instead of using the on-disk cache");

  std::vector<std::string> run_cases;
  bool strict = false, update = false;
  CLI::App* run = app.add_subcommand("run", "replay cases and compare them with their golden logs");
  run->add_option("cases", run_cases, "case folders, .yaml files, or folders of cases")->required();
  run->add_flag("--strict", strict, "a differing trajectory hash fails the case too");
  run->add_flag("--update", update, "record the golden logs of the cases that differ (review the diff!)");
  std::filesystem::path html_dir;
  run->add_option("--html", html_dir, "write each case's replay viewer (one HTML page, docs/viewer.md) as DIR/CASE.html");

  std::vector<std::string> record_cases;
  CLI::App* rec = app.add_subcommand("record", "write the golden logs of cases");
  rec->add_option("cases", record_cases, "case folders, .yaml files, or folders of cases")->required();

  std::string map, motion, out, agent = "pursuer_0", scenario;
  std::vector<std::string> sets;
  CLI::App* make = app.add_subcommand("new", "make a case from a map and a motion file, and record it");
  make->add_option("--map", map, "the map (YAML)")->required();
  make->add_option("--motion", motion, "NAME.commands (timed steering) or NAME.waypoints")->required();
  make->add_option("--out", out, "the case folder to create")->required();
  make->add_option("--agent", agent, "the agent the motion drives (pursuer_0, evader_0, pursuer_1, ...)")->capture_default_str();
  make->add_option("--scenario", scenario, "the map's scenario (default: its first)");
  make->add_option("--set", sets, "configuration overrides, key=value (repeatable)");

  return cli::guarded_main(app, argc, argv, [&] {
    const bool use_cache = !no_cache;
    if (rec->parsed()) {
      for (const auto& path : expand(record_cases)) record(regress::load_case(path), use_cache);
      return 0;
    }
    if (make->parsed()) {
      const std::filesystem::path dir(out);
      const std::filesystem::path motion_file(motion);
      const std::string kind = motion_kind(motion_file);
      if (kind == "commands") regress::read_commands(motion_file);  // refuse a bad file before writing anything
      if (kind == "waypoints") regress::read_waypoints(motion_file);
      const std::filesystem::path map_file = cli::resolve_input(map);
      world::load_map(map_file);
      if (std::filesystem::exists(dir / "case.yaml")) throw InputError(dir / "case.yaml", 0, "", "exists already");
      // A case that cannot be recorded (an unknown scenario or agent, a bad override) leaves nothing behind.
      const bool made_dir = !std::filesystem::exists(dir);
      std::filesystem::create_directories(dir);
      try {
        const std::filesystem::path motion_copy = dir / motion_file.filename();
        std::filesystem::copy_file(motion_file, motion_copy, std::filesystem::copy_options::overwrite_existing);
        std::string text = fmt::format("# made by peg-collide new\nmap: {}\n",
                                       std::filesystem::relative(std::filesystem::absolute(map_file), std::filesystem::absolute(dir)).string());
        if (!scenario.empty()) text += fmt::format("scenario: {}\n", scenario);
        if (!sets.empty()) {
          text += "set:\n";
          for (const auto& s : sets) text += fmt::format("  - {}\n", s);
        }
        text += fmt::format("agents:\n  {}: {{{}: {}}}\n", agent, kind, motion_copy.filename().string());
        write_file_atomically(dir / "case.yaml", text);
        record(regress::load_case(dir), use_cache);
      } catch (...) {
        std::error_code ec;
        if (made_dir) {
          std::filesystem::remove_all(dir, ec);
        } else {
          std::filesystem::remove(dir / "case.yaml", ec);
          std::filesystem::remove(dir / motion_file.filename(), ec);
        }
        throw;
      }
      return 0;
    }
    // run
    int differing = 0;
    for (const auto& path : expand(run_cases)) {
      const regress::CollisionCase c = regress::load_case(path);
      const regress::CollisionLog expected = regress::parse_log(read_text(c.golden), c.golden);
      const regress::CasePlay play = regress::play_case(c, use_cache);
      const regress::CollisionLog& actual = play.log;
      if (!html_dir.empty()) {
        cli::prepare_output_dir(html_dir);
        const std::filesystem::path file = results::output_file(html_dir, c.name, ".html");
        cli::write_case_viewer(file, c, play);
      }
      std::vector<std::string> notes;
      const auto diffs = regress::compare_logs(expected, actual, regress::Tolerances{}, strict, &notes);
      for (const auto& n : notes) std::printf("note %s: %s\n", c.name.c_str(), n.c_str());
      if (diffs.empty()) {
        std::printf("ok   %s (%zu collision(s), %zu capture(s), %s)\n", c.name.c_str(), actual.events.size(),
                    actual.captures.size(), actual.outcome.c_str());
        continue;
      }
      ++differing;
      std::printf("FAIL %s\n", c.name.c_str());
      for (const auto& d : diffs) std::printf("%s: %s\n", c.name.c_str(), d.c_str());
      if (update) {
        write_file_atomically(c.golden, regress::format_log(actual));
        std::printf("updated %s\n", c.golden.string().c_str());
      }
    }
    return differing == 0 || update ? 0 : 1;
  });
}
