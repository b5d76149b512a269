#include "experiment/result_files.hpp"

#include <fstream>
#include <sstream>

#include "experiment/atomic_file.hpp"
#include "experiment/csv_writer.hpp"
#include "game/facl_policy.hpp"
#include "game/policy_io.hpp"
#include "geometry/apollonius.hpp"
#include "geometry/motion_cone.hpp"

namespace peg3d::experiment {
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
                               const std::vector<std::vector<game::EpisodeResult>>& curves) {
  AtomicFile out(file);
  CsvWriter csv(out.stream(), with_episode_columns({"scenario", "algorithm", "repeat", "episode"}));
  for (std::size_t i = 0; i < runs.size(); ++i) {
    for (std::size_t k = 0; k < curves[i].size(); ++k) {
      auto row = csv.row();
      row.add(runs[i].scenario).add(runs[i].algorithm).add(runs[i].repeat).add(k);
      add_episode_cells(row, curves[i][k]);
      row.end();
    }
  }
  out.commit();
}

void write_trajectory_csv(const std::filesystem::path& file, const std::vector<game::StepRecord>& steps) {
  std::vector<std::string> columns{"t",             "pursuer_x",     "pursuer_y",   "pursuer_z",   "evader_x",
                                   "evader_y",      "evader_z",      "pursuer_alpha", "pursuer_theta", "evader_alpha",
                                   "evader_theta",  "distance"};
  for (const char* a : {"pursuer", "evader"}) {
    for (const char* c : {"d_target", "target_az", "target_el", "d_obstacle", "obstacle_az", "obstacle_el", "d_alpha",
                          "d_theta", "reward", "pinned"}) {
      columns.push_back(std::string(a) + "_" + c);
    }
  }
  AtomicFile out(file);
  CsvWriter csv(out.stream(), columns);
  for (const game::StepRecord& s : steps) {
    auto row = csv.row();
    row.add(s.time);
    for (const Vec3& p : {s.pursuer.position, s.evader.position}) row.add(p.x()).add(p.y()).add(p.z());
    row.add(s.pursuer.heading.alpha).add(s.pursuer.heading.theta).add(s.evader.heading.alpha).add(s.evader.heading.theta);
    row.add((s.pursuer.position - s.evader.position).norm());
    const auto agent = [&](const game::Percept& q, const Steering& u, double reward) {
      row.add(q.target_distance)
          .add(q.target.azimuth)
          .add(q.target.elevation)
          .add(q.obstacle.distance)
          .add(q.to_obstacle.azimuth)
          .add(q.to_obstacle.elevation)
          .add(u.d_alpha)
          .add(u.d_theta)
          .add(reward)
          .add(static_cast<int>(q.pinned));
    };
    agent(s.pursuer_percept, s.pursuer_steering, s.pursuer_reward);
    agent(s.evader_percept, s.evader_steering, s.evader_reward);
    row.end();
  }
  out.commit();
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
    j["scenarios"].push_back({{"name", s.name}, {"pursuer", vec(s.pursuer.position)}, {"evader", vec(s.evader.position)}});
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

bool save_policy(const std::filesystem::path& file, const game::Policy& policy) {
  const auto* facl = dynamic_cast<const game::FaclPolicy*>(&policy);
  if (facl == nullptr) return false;
  write_json(file, game::policy_to_json(*facl));
  return true;
}

std::unique_ptr<game::Policy> load_policy(const std::filesystem::path& file, std::uint64_t seed) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open policy file");
  try {
    return game::policy_from_json(nlohmann::json::parse(in), seed);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(file.string() + ": not JSON: " + e.what());
  } catch (const game::PolicyFormatError& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
}

}  // namespace peg3d::experiment
