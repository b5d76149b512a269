#include "results/result_files.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/input_files.hpp"
#include "geometry/apollonius.hpp"
#include "geometry/motion_cone.hpp"
#include "results/csv_writer.hpp"

namespace peg3d::results {
namespace {

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

std::vector<std::string> with_episode_columns(std::vector<std::string> leading) {
  for (const char* c : {"outcome", "captured", "capture_time_s", "episode_time_s", "final_distance_m", "pursuer_path_m",
                        "evader_path_m", "collisions", "evader_pinned_fraction", "pursuer_pinned_fraction",
                        "pursuer_return", "evader_return"}) {
    leading.emplace_back(c);
  }
  return leading;
}

void add_episode_cells(CsvWriter::Row& row, const game::EpisodeResult& e) {
  row.add(game::to_string(e.outcome))
      .add(static_cast<int>(e.captured()))
      .add(e.captured() ? e.duration : std::numeric_limits<double>::quiet_NaN())
      .add(e.duration)
      .add(e.final_distance)
      .add(e.pursuer_path)
      .add(e.evader_path)
      .add(e.collisions)
      .add(e.pinned_fraction(game::Role::kEvader))
      .add(e.pinned_fraction(game::Role::kPursuer))
      .add(e.pursuer_return)
      .add(e.evader_return);
}

void write_runs_csv(const std::filesystem::path& file, const std::vector<RunRecord>& runs) {
  AtomicFile out(file);
  CsvWriter csv(out.stream(), with_episode_columns({"scenario", "algorithm", "repeat", "seed", "train_captures"}));
  for (const RunRecord& r : runs) {
    auto row = csv.row();
    row.add(r.scenario).add(r.algorithm).add(r.repeat).add(r.seed).add(r.train_captures);
    add_episode_cells(row, r.evaluation);
    row.end();
  }
  out.commit();
}

void write_learning_curves_csv(const std::filesystem::path& file, const std::vector<RunRecord>& runs,
                               const std::vector<LearningCurve>& curves) {
  AtomicFile out(file);
  CsvWriter csv(out.stream(), with_episode_columns({"scenario", "algorithm", "repeat", "episode", "pool_opponent"}));
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const LearningCurve& c = curves[i];
    if (c.pool_opponents.size() != c.episodes.size()) throw std::logic_error("learning curve: one opponent per episode");
    for (std::size_t k = 0; k < c.episodes.size(); ++k) {
      auto row = csv.row();
      row.add(runs[i].scenario).add(runs[i].algorithm).add(runs[i].repeat).add(k).add(c.pool_opponents[k]);
      add_episode_cells(row, c.episodes[k]);
      row.end();
    }
  }
  out.commit();
}

std::filesystem::path output_file(const std::filesystem::path& folder, const std::string& name, const char* extension) {
  // Scenario names are checked when the map is read (world::is_safe_name); this guards every other way a
  // name can arrive (maps built in code), so no result is ever written outside `folder`.
  bool ok = !name.empty() && name.size() <= 200 && name.front() != '.';
  for (const char c : name) {
    ok = ok && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.');
  }
  if (!ok) {
    throw InputError(fmt::format("'{}' cannot name a result file in {}: names may use letters, digits, '-', '_' and "
                                 "'.', not starting with '.'",
                                 name, folder.string()));
  }
  return folder / (name + extension);
}

void write_json(const std::filesystem::path& file, const nlohmann::json& value) {
  write_file_atomically(file, value.dump(2) + "\n");
}

void write_json(const std::filesystem::path& file, const nlohmann::ordered_json& value) {
  write_file_atomically(file, value.dump(2) + "\n");
}

nlohmann::json map_to_json(const world::Arena& arena) {
  const world::MapSpec& m = arena.map();
  nlohmann::json j{{"name", m.name}, {"bounds", {{"lo", vec(m.bounds.lo)}, {"hi", vec(m.bounds.hi)}}}};
  j["spheres"] = nlohmann::json::array();
  for (const auto& s : m.spheres) j["spheres"].push_back({{"center", vec(s.center)}, {"radius", s.radius}});
  j["cylinders"] = nlohmann::json::array();
  for (const auto& c : m.cylinders) {
    j["cylinders"].push_back({{"base", vec(c.base)}, {"radius", c.radius}, {"height", c.height}});
  }
  j["meshes"] = nlohmann::json::array();
  for (std::size_t i = 0; i < arena.meshes().size(); ++i) {
    const world::TriangleMesh& mesh = arena.meshes()[i];
    nlohmann::json v = nlohmann::json::array(), t = nlohmann::json::array();
    for (const Vec3& p : mesh.vertices) v.push_back(vec(p));
    for (const auto& tri : mesh.faces) t.push_back({tri[0], tri[1], tri[2]});
    j["meshes"].push_back({{"file", m.meshes[i].file.string()}, {"vertices", v}, {"triangles", t}});
  }
  j["scenarios"] = nlohmann::json::array();
  for (const auto& s : m.scenarios) {
    nlohmann::json sc{{"name", s.name}, {"pursuers", nlohmann::json::array()}, {"evaders", nlohmann::json::array()}};
    for (const auto& a : s.pursuers) sc["pursuers"].push_back(vec(a.position));
    for (const auto& a : s.evaders) sc["evaders"].push_back(vec(a.position));
    // The first of each role under the singular key, as plots of one-against-one games read it.
    sc["pursuer"] = vec(s.pursuers.front().position);
    sc["evader"] = vec(s.evaders.front().position);
    j["scenarios"].push_back(std::move(sc));
  }
  return j;
}

nlohmann::json apollonius_to_json(const Vec3& p, const Vec3& e, double vp, double ve, const std::vector<double>& ratios) {
  nlohmann::json out{{"pursuer", vec(p)}, {"evader", vec(e)}, {"vp", vp}, {"ve", ve}};
  out["surfaces"] = nlohmann::json::array();
  for (double a : ratios) {
    const ApolloniusSurface s(p, e, a);
    if (s.is_plane()) {
      out["surfaces"].push_back({{"a", a}, {"kind", "plane"}, {"point", vec(s.plane().point)}, {"normal", vec(s.plane().normal)}});
    } else {
      out["surfaces"].push_back({{"a", a},
                                 {"kind", "sphere"},
                                 {"center", vec(s.sphere().center)},
                                 {"radius", s.sphere().radius},
                                 {"encloses", a < 1.0 ? "evader" : "pursuer"}});
    }
  }
  const Cone pc = pursuer_motion_cone(p, e, vp, ve);
  const Cone ec = evader_motion_cone(p, e);
  out["pursuer_cone"] = {{"axis", vec(pc.axis)}, {"half_angle_rad", pc.half_angle}};
  out["evader_cone"] = {{"axis", vec(ec.axis)}, {"half_angle_rad", ec.half_angle}};
  if (ve > 0.0) {
    // Where a pursuer heading straight for it meets an evader fleeing straight away from it.
    if (const auto x = interception_point(p, e, ec.axis, ve / vp)) out["interception_fleeing"] = vec(*x);
  }
  return out;
}

}  // namespace peg3d::results
