// peg-map: inspect a map. Loads it, builds the world (octree, distance field; cached on disk) and reports.
//   peg-map check MAP.yaml                       what the map holds, build time and memory; checks every start
//                                                against the agents of the default game configuration
//   peg-map distance MAP.yaml X Y Z              distance to the nearest obstacle and its position
//   peg-map export MAP.yaml --octree OUT.bt [--time T]   the octree as an OctoMap .bt file (view with
//                                                octovis), with the moving obstacles where they are at T s
//   peg-map movers MAP.yaml --seconds T [--every K]   every mover's pose over time, as CSV
// Bad input prints "error: FILE:LINE: message" on stderr and exits with status 2, writing nothing.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli_common.hpp"
#include "game/sim.hpp"
#include "world/arena.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"
#include "world/bodies/mover_timeline.hpp"

namespace {

using peg3d::world::Arena;
using peg3d::world::BuildOptions;

struct Common {
  std::string map;
  std::optional<double> resolution;
  bool no_cache = false;
  std::string cache_dir;
  double max_field_mib = 4096.0;
};

void add_common(CLI::App& cmd, Common& c) {
  cmd.add_option("map", c.map, "map file (YAML, see docs/maps.md)")->required();
  cmd.add_option("--resolution", c.resolution, "voxel edge in m, replaces the map's occupancy.resolution");
  cmd.add_flag("--no-cache", c.no_cache, "build from scratch and do not store the result");
  cmd.add_option("--cache-dir", c.cache_dir,
                 "cache folder (default $PEG3D_CACHE_DIR, else $XDG_CACHE_HOME/peg3d, else ~/.cache/peg3d)");
  cmd.add_option("--max-field-mib", c.max_field_mib, "refuse distance fields needing more memory than this (MiB)")
      ->check(CLI::PositiveNumber);
}

std::shared_ptr<const Arena> build(const Common& c) {
  const peg3d::world::MapSpec spec = peg3d::world::load_map(peg3d::cli::resolve_input(c.map));
  BuildOptions options;
  options.resolution_override = c.resolution;
  if (!c.no_cache) options.cache_dir = c.cache_dir.empty() ? peg3d::world::default_cache_dir() : std::filesystem::path(c.cache_dir);
  options.max_field_bytes = static_cast<std::size_t>(c.max_field_mib * 1048576.0);
  return Arena::build(spec, options);
}

std::string mib(double bytes) { return fmt::format("{:.1f} MiB", bytes / 1048576.0); }
std::string vec(const peg3d::Vec3& v) { return fmt::format("({:g}, {:g}, {:g})", v.x(), v.y(), v.z()); }

double peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) * 1024.0;  // Linux reports KiB
}

void print_check(const Arena& arena) {
  const auto& m = arena.map();
  const auto& s = arena.stats();
  std::string faces;
  auto add_face = [&](bool on, const char* name) {
    if (on) faces += faces.empty() ? name : fmt::format(", {}", name);
  };
  add_face(m.floor_is_obstacle, "floor");
  add_face(m.ceiling_is_obstacle, "ceiling");
  add_face(m.walls_is_obstacle, "walls");
  std::string names;
  for (const auto& sc : m.scenarios) names += (names.empty() ? "" : ", ") + sc.name;
  fmt::print("map        {}{}\n", m.source.string(), m.name.empty() ? "" : fmt::format(" ({})", m.name));
  fmt::print("arena      {} .. {} m, size {} m; faces that are obstacles: {}\n", vec(m.bounds.lo), vec(m.bounds.hi),
             vec(m.bounds.size()), faces.empty() ? "none" : faces);
  fmt::print("obstacles  {} spheres, {} cylinders, {} meshes ({} triangles)\n", s.spheres, s.cylinders, s.meshes,
             s.triangles);
  fmt::print("scenarios  {}: {}\n", m.scenarios.size(), names);
  if (!m.movers.empty()) {
    int dynamic = 0;
    for (const auto& mv : m.movers) dynamic += !mv.kinematic();
    fmt::print("movers     {} ({} scripted, {} dynamic); physics {} Hz, gravity {}, faces {}\n", m.movers.size(),
               m.movers.size() - dynamic, dynamic, m.physics.rate_hz, vec(m.physics.gravity),
               m.physics.faces_are_physical ? "physical" : "not physical");
  }
  fmt::print("octree     resolution {:g} m, {} occupied voxels, {} as .bt\n", s.resolution, s.occupied_voxels,
             mib(double(s.octree_bytes)));
  fmt::print("distance   {} x {} x {} = {} cells, cap {:g} m, {} kept ({} B/cell)\n", s.field_dims[0], s.field_dims[1],
             s.field_dims[2], s.field_cells, m.max_distance, mib(double(s.field_bytes)),
             s.field_cells ? s.field_bytes / s.field_cells : 0);
  if (s.loaded_from_cache) {
    fmt::print("build      {:.3f} s, loaded from the cache\n", s.build_seconds);
  } else {
    fmt::print("build      {:.3f} s (voxelize {:.3f} s, octree {:.3f} s, distance field {:.3f} s), estimated peak {}\n",
               s.build_seconds, s.voxelize_seconds, s.octree_seconds, s.edt_seconds, mib(double(s.build_peak_bytes)));
  }
  fmt::print("cache      {}{}\n", s.cache_status, s.cache_file.empty() ? "" : fmt::format(": {}", s.cache_file.string()));
  fmt::print("peak RSS   {}\n", mib(peak_rss_bytes()));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"peg-map: check a peg3d map, query its distance field, export its octree"};
  app.require_subcommand(1);
  Common common;

  CLI::App* check = app.add_subcommand("check", "load MAP and print what it holds, build time and memory");
  add_common(*check, common);
  bool motion = false;
  check->add_flag("--motion", motion,
                  "also simulate the movers over a whole game of the default configuration and say what it took "
                  "(time and memory of the timeline)");

  CLI::App* distance = app.add_subcommand("distance", "distance from (X, Y, Z) to the nearest obstacle");
  add_common(*distance, common);
  double x = 0, y = 0, z = 0;
  distance->add_option("x", x, "m")->required();
  distance->add_option("y", y, "m")->required();
  distance->add_option("z", z, "m")->required();

  CLI::App* exporter = app.add_subcommand("export", "write the octree of MAP as an OctoMap .bt file");
  add_common(*exporter, common);
  std::string octree_out;
  std::optional<double> export_time;
  exporter->add_option("--octree", octree_out, "output .bt file")->required();
  exporter->add_option("--time", export_time, "mark the moving obstacles where they are at this time (s)")
      ->check(CLI::NonNegativeNumber);

  CLI::App* movers_cmd = app.add_subcommand("movers", "every moving obstacle's pose over time, as CSV on stdout");
  add_common(*movers_cmd, common);
  double seconds = 10.0;
  int every = 24;
  movers_cmd->add_option("--seconds", seconds, "how long (s)")->capture_default_str()->check(CLI::Range(0.0, 3600.0));
  movers_cmd->add_option("--every", every, "print every K-th physics substep (24 at 240 Hz: every 0.1 s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);

  return peg3d::cli::guarded_main(app, argc, argv, [&] {
    if (distance->parsed() && !(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
      throw peg3d::InputError("the query point must be finite");
    }
    const auto arena = build(common);
    if (check->parsed()) {
      print_check(*arena);
      // Starts are points in a map; whether the agents' spheres fit there is the game's check (StartError).
      const peg3d::game::Sim sim(arena, peg3d::game::preset("peg3d"));
      fmt::print("starts     every agent of every scenario fits (radii {:g} m and {:g} m)\n",
                 sim.config().pursuer.radius, sim.config().evader.radius);
      if (const auto* timeline = sim.movers()) {
        if (motion) timeline->simulate_all();
        const auto t = timeline->stats();
        fmt::print("motion     {:g} s, {} dynamic bodies at {} keyframes/s in {} blocks; worst case {} (budget {})\n",
                   timeline->duration(), t.dynamic_bodies, t.keyframe_hz, t.blocks, mib(double(t.worst_case_bytes)),
                   mib(double(peg3d::world::MoverTimeline::kMaxBytes)));
        if (t.dynamic_bodies > 0 && t.keyframe_hz_chosen) {
          if (timeline->keyframe_stride() == 1) {
            fmt::print("keyframes  every substep ({}/s): the map sets no physics.keyframe_hz, and every substep fits\n",
                       t.keyframe_hz);
          } else {
            fmt::print("keyframes  {}/s (one every {} substeps), chosen: the map sets no physics.keyframe_hz, and "
                       "every substep would need up to {}; the highest rate dividing rate_hz = {} within the budget\n",
                       t.keyframe_hz, timeline->keyframe_stride(), mib(double(t.every_substep_bytes)),
                       timeline->rate_hz());
          }
        }
        if (motion) {
          fmt::print("simulated  in {:.3f} s, {} held; {} body-blocks at rest stored once, {} moving\n",
                     t.simulate_seconds, mib(double(t.bytes)), t.resting_entries, t.moving_entries);
          fmt::print("peak RSS   {}\n", mib(peak_rss_bytes()));
        }
      }
    } else if (distance->parsed()) {
      const peg3d::Vec3 p(x, y, z);
      const auto n = arena->nearest_obstacle(p);
      if (!arena->bounds().contains(p)) fmt::print("note: {} lies outside the arena; answered from its edge\n", vec(p));
      if (n.found) {
        const peg3d::Vec3 dir = (n.point - p).normalized();
        fmt::print("distance {:.4f} m to the obstacle voxel point {}, direction {}\n", n.distance, vec(n.point),
                   n.distance > 0 ? vec(dir) : std::string("(inside)"));
      } else {
        fmt::print("distance {:g} m (cap): no obstacle within occupancy.max_distance\n", n.distance);
      }
    } else if (exporter->parsed()) {
      if (export_time) {
        arena->save_octree(octree_out, *export_time);
      } else {
        arena->save_octree(octree_out);
      }
      fmt::print("wrote {} ({}, resolution {:g} m, {} occupied voxels)\n", octree_out,
                 mib(double(arena->stats().octree_bytes)), arena->resolution(), arena->stats().occupied_voxels);
    }
    if (movers_cmd->parsed()) {
      const auto timeline = arena->movers_until(seconds);
      fmt::print("t,id,kind,x,y,z,qw,qx,qy,qz\n");
      if (!timeline) return 0;
      const long substeps = static_cast<long>(std::llround(seconds * timeline->rate_hz()));
      for (long k = 0; k <= substeps; k += every) {
        const double t = static_cast<double>(k) / timeline->rate_hz();
        for (int m = 0; m < timeline->count(); ++m) {
          const peg3d::Pose p = timeline->pose(m, t);
          fmt::print("{},{},{},{},{},{},{},{},{},{}\n", t, m, peg3d::to_string(timeline->mover(m).shape.kind),
                     p.position.x(), p.position.y(), p.position.z(), p.orientation.w(), p.orientation.x(),
                     p.orientation.y(), p.orientation.z());
        }
      }
    }
    return 0;
  });
}
