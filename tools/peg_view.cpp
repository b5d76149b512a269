// peg-view: one recorded episode as a self-contained HTML replay viewer (docs/viewer.md).
//   peg-view --map MAP --trajectory FILE.csv [--config NAME|FILE] [--set k=v]... [--out FILE.html]
//                                   a trajectory file written by an experiment, on the map it was played on
//   peg-view --case CASE [--out FILE.html]
//                                   a collision-regression case, played headless and recorded
// Exit status: 0 when the file was written, 2 on bad input (map, trajectory, case, configuration), 1 otherwise.

#include <cstdio>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "game/config_file.hpp"
#include "regress/collision_case.hpp"
#include "results/trajectory_file.hpp"
#include "view/replay.hpp"

using namespace peg3d;

namespace {

// What a trajectory file says about its ending: every evader captured, a collision, or neither.
std::string ending_of_trace(const game::Trace& t) {
  int evaders = 0;
  for (const auto r : t.roles) evaders += r == game::Role::kEvader;
  const double end = t.times.back();
  if (!t.captures.empty() && static_cast<int>(t.captures.size()) == evaders) return fmt::format("capture at {:.1f} s", end);
  if (!t.collisions.empty()) return fmt::format("{} collision(s), ended at {:.1f} s", t.collisions.size(), end);
  return fmt::format("ended at {:.1f} s", end);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"peg-view: a recorded episode as a self-contained HTML replay viewer"};
  std::filesystem::path map, trajectory, case_path, out;
  std::string config_source = "peg3d", title;
  std::vector<std::string> sets;
  std::size_t max_triangles = view::ReplaySettings{}.max_drawn_triangles;
  bool no_cache = false;
  auto* map_opt = app.add_option("--map", map, "the map the trajectory was played on (YAML)");
  auto* traj_opt = app.add_option("--trajectory", trajectory, "a trajectory file (trajectories/*.csv of an experiment)");
  auto* case_opt = app.add_option("--case", case_path, "a collision-regression case (folder with case.yaml, or NAME.yaml)");
  app.add_option("--config", config_source,
                 "with --trajectory: the configuration the agents played (preset or JSON file; radii and speeds)")
      ->capture_default_str();
  app.add_option("--set", sets, "with --trajectory: configuration overrides, key=value (repeatable)");
  app.add_option("--out", out, "the HTML file (default: the trajectory's name with .html, or CASE.html here)");
  app.add_option("--title", title, "the page's title (default: from the input)");
  app.add_option("--max-triangles", max_triangles, "terrain triangles drawn at most (larger terrains are simplified)")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1000}, std::size_t{5'000'000}));
  app.add_flag("--no-cache", no_cache, "rebuild the world instead of using the on-disk cache");
  traj_opt->needs(map_opt);
  map_opt->needs(traj_opt);
  case_opt->excludes(map_opt)->excludes(traj_opt);

  return cli::guarded_main(app, argc, argv, [&] {
    if (case_path.empty() && trajectory.empty()) throw CLI::ValidationError("give --map and --trajectory, or --case");
    view::ReplaySettings settings;
    settings.max_drawn_triangles = max_triangles;
    if (!case_path.empty()) {
      const regress::CollisionCase c = regress::load_case(case_path);
      const regress::CasePlay play = regress::play_case(c, !no_cache);
      if (out.empty()) out = c.name + ".html";
      const auto bytes = cli::write_case_viewer(out, c, play, title, settings);
      std::printf("%s: %d frames, %.1f MB\n", out.string().c_str(), play.trace.frame_count(), double(bytes) / 1e6);
      return 0;
    }
    const game::Trace trace = results::read_trajectory_csv(trajectory);
    game::GameConfig config = game::apply_game_overrides(game::load_game_config(config_source), sets);
    // The movers' motion must cover the whole recording, however long the experiment let it run.
    config.time_limit = std::max(config.time_limit, trace.times.back() + config.dt);
    const auto arena = cli::load_arena(map, !no_cache);
    const game::Sim sim(arena, config);
    if (out.empty()) out = std::filesystem::path(trajectory).replace_extension(".html");
    const view::ReplayScene scene(*arena, settings);
    const std::string heading = title.empty() ? trajectory.stem().string() : title;
    const auto bytes = cli::write_viewer(
        out, scene, sim, trace,
        {heading, fmt::format("{} on {}; {}", trajectory.filename().string(), map.filename().string(), ending_of_trace(trace))});
    std::printf("%s: %d frames, %zu terrain triangles drawn, %.1f MB\n", out.string().c_str(), trace.frame_count(),
                scene.drawn_triangles(), double(bytes) / 1e6);
    return 0;
  });
}
