#include "view/replay.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

#include <fmt/format.h>
#include <meshoptimizer.h>

#include "geometry/apollonius.hpp"
#include "geometry/motion_cone.hpp"

namespace peg3d::view {
namespace {

// The viewer decodes the series as little-endian typed arrays straight from the bytes.
static_assert(std::endian::native == std::endian::little, "replay series are written as raw little-endian bytes");

template <class T>
std::string encoded(const std::vector<T>& values) {
  return base64(values.data(), values.size() * sizeof(T));
}

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

void push(std::vector<float>& out, const Vec3& v) {
  out.push_back(static_cast<float>(v.x()));
  out.push_back(static_cast<float>(v.y()));
  out.push_back(static_cast<float>(v.z()));
}

// The frames at which movers and pair geometry are sampled: all, or `cap` evenly spread with both ends.
std::vector<std::uint32_t> sample_frames(int frames, int cap) {
  std::vector<std::uint32_t> out;
  if (frames <= cap) {
    for (int k = 0; k < frames; ++k) out.push_back(std::uint32_t(k));
    return out;
  }
  for (int s = 0; s < cap; ++s) {
    out.push_back(std::uint32_t(std::llround(double(s) * double(frames - 1) / double(cap - 1))));
  }
  return out;
}

}  // namespace

DrawnMesh drawn_mesh(const world::TriangleMesh& mesh, std::size_t max_triangles, std::string name) {
  assert(max_triangles >= 1);
  DrawnMesh out;
  out.name = std::move(name);
  out.source_triangles = mesh.faces.size();
  std::vector<float> positions;
  positions.reserve(mesh.vertices.size() * 3);
  for (const Vec3& v : mesh.vertices) push(positions, v);
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.faces.size() * 3);
  for (const auto& f : mesh.faces) {
    for (int c : f) indices.push_back(std::uint32_t(c));
  }
  const std::size_t vertex_count = mesh.vertices.size();
  if (mesh.faces.size() > max_triangles) {
    // Topology-preserving first (1 % of the extent); where that stops short of the budget, the sloppy
    // simplifier, which always reaches it.
    std::vector<std::uint32_t> simplified(indices.size());
    std::size_t n = meshopt_simplify(simplified.data(), indices.data(), indices.size(), positions.data(), vertex_count,
                                     sizeof(float) * 3, max_triangles * 3, 0.01f, 0, nullptr);
    if (n > max_triangles * 3) {
      n = meshopt_simplifySloppy(simplified.data(), indices.data(), indices.size(), positions.data(), vertex_count,
                                 sizeof(float) * 3, max_triangles * 3, 1.0f, nullptr);
    }
    simplified.resize(n);
    indices = std::move(simplified);
  }
  // Only the vertices the drawn triangles use, in the order they are first used.
  std::vector<float> compact(positions.size());
  const std::size_t used = meshopt_optimizeVertexFetch(compact.data(), indices.data(), indices.size(), positions.data(),
                                                       vertex_count, sizeof(float) * 3);
  compact.resize(used * 3);
  out.positions = std::move(compact);
  out.indices = std::move(indices);
  return out;
}

ReplayScene::ReplayScene(const world::Arena& arena, const ReplaySettings& settings) : settings_(settings) {
  assert(settings.max_drawn_triangles >= 1000 && settings.max_pose_samples >= 2);
  const world::MapSpec& m = arena.map();
  json_ = {{"format", "peg3d-replay"}, {"version", 1}, {"map", m.name},
           {"arena", {{"lo", vec(m.bounds.lo)}, {"hi", vec(m.bounds.hi)}}}};
  json_["spheres"] = nlohmann::json::array();
  for (const auto& s : m.spheres) json_["spheres"].push_back({{"center", vec(s.center)}, {"radius", s.radius}});
  json_["cylinders"] = nlohmann::json::array();
  for (const auto& c : m.cylinders) {
    json_["cylinders"].push_back({{"base", vec(c.base)}, {"radius", c.radius}, {"height", c.height}});
  }
  std::size_t total = 0;
  for (const auto& mesh : arena.meshes()) total += mesh.triangle_count();
  json_["meshes"] = nlohmann::json::array();
  for (std::size_t i = 0; i < arena.meshes().size(); ++i) {
    const world::TriangleMesh& mesh = arena.meshes()[i];
    // Each mesh's share of the budget follows its size (at least one triangle each).
    const std::size_t share =
        total <= settings.max_drawn_triangles
            ? mesh.triangle_count()
            : std::max<std::size_t>(1, std::size_t(double(settings.max_drawn_triangles) * double(mesh.triangle_count()) /
                                                   double(total)));
    const DrawnMesh d = drawn_mesh(mesh, std::max<std::size_t>(share, 1), m.meshes[i].file.filename().string());
    drawn_triangles_ += d.triangle_count();
    json_["meshes"].push_back({{"name", d.name},
                               {"triangles", d.source_triangles},
                               {"drawn_triangles", d.triangle_count()},
                               {"positions_f32", encoded(d.positions)},
                               {"indices_u32", encoded(d.indices)}});
  }
  json_["movers"] = nlohmann::json::array();
  for (const auto& mv : m.movers) {
    json_["movers"].push_back({{"shape", to_string(mv.shape.kind)},
                               {"radius", mv.shape.radius},
                               {"height", mv.shape.height},
                               {"size", vec(mv.shape.size)},
                               {"dynamic", !mv.kinematic()}});
  }
}

namespace {

// Agent i's recorded track, every frame: position, heading, activity, the vector to its nearest obstacle, its
// fuzzy inputs, actions and rewards.
nlohmann::json agent_track(const game::Trace& trace, int i) {
  std::vector<float> position, heading, obstacle, inputs, action, reward;
  std::vector<std::uint8_t> active;
  for (int k = 0; k < trace.frame_count(); ++k) {
    const game::AgentFrame& f = trace.at(k, i);
    push(position, f.state.position);
    heading.push_back(float(f.state.heading.alpha));
    heading.push_back(float(f.state.heading.theta));
    active.push_back(f.active ? 1 : 0);
    push(obstacle, f.percept.obstacle.found ? Vec3(f.percept.obstacle.point - f.state.position) : Vec3::Zero());
    const game::Percept& q = f.percept;
    for (double v : {q.target_distance, q.target.azimuth, q.target.elevation, q.obstacle.distance,
                     q.to_obstacle.azimuth, q.to_obstacle.elevation}) {
      inputs.push_back(float(v));
    }
    action.push_back(float(f.command.d_alpha));
    action.push_back(float(f.command.d_theta));
    reward.push_back(float(f.reward));
  }
  return {{"position_f32", encoded(position)}, {"heading_f32", encoded(heading)}, {"active_u8", encoded(active)},
          {"obstacle_f32", encoded(obstacle)}, {"inputs_f32", encoded(inputs)},   {"action_f32", encoded(action)},
          {"reward_f32", encoded(reward)}};
}

// Agent i's limited sight (its detector's knowledge): at every frame the opponent it looked for (0xffffffff: not
// recorded, as in a trace from an older journal), whether it saw it and where it took it to be.
void add_knowledge(nlohmann::json& layer, const game::Trace& trace, int i) {
  std::vector<std::uint32_t> opponent;
  std::vector<std::uint8_t> visible;
  std::vector<float> estimate;
  for (int f = 0; f < trace.frame_count(); ++f) {
    const game::AgentFrame& a = trace.at(f, i);
    opponent.push_back(a.opponent >= 0 ? std::uint32_t(a.opponent) : 0xffffffffu);
    visible.push_back(a.sees ? 1 : 0);
    push(estimate, a.estimate);
  }
  layer["opponent_u32"] = encoded(opponent);
  layer["visible_u8"] = encoded(visible);
  layer["estimate_f32"] = encoded(estimate);
}

// Agent i's own map as it grows: the cells occupied at frame 0, then each change, in order.
nlohmann::json agent_map(const game::Trace& trace, int i, double resolution) {
  std::vector<std::uint32_t> frames;
  std::vector<float> centres;
  std::vector<std::uint8_t> occupied;
  for (const game::MapFlip& m : trace.map_flips) {
    if (m.agent != i) continue;
    frames.push_back(std::uint32_t(m.frame));
    push(centres, m.centre);
    occupied.push_back(m.occupied ? 1 : 0);
  }
  return {{"resolution", resolution}, {"flip_frames_u32", encoded(frames)}, {"flip_centres_f32", encoded(centres)},
          {"flip_occupied_u8", encoded(occupied)}};
}

// Each mover's pose at the sampled frames, into the scene's movers.
void mover_poses(nlohmann::json& j, const world::MoverTimeline& movers, const game::Trace& trace,
                 const std::vector<std::uint32_t>& samples) {
  for (int m = 0; m < movers.count(); ++m) {
    std::vector<float> poses;
    poses.reserve(samples.size() * 7);
    for (std::uint32_t k : samples) {
      // A push-mode run moved the bodies itself: the trace has their poses.
      const Pose p = trace.movers > 0 ? trace.body_poses[std::size_t(k) * std::size_t(trace.movers) + std::size_t(m)]
                                      : movers.pose(m, trace.times[k]);
      push(poses, p.position);
      for (double q : {p.orientation.x(), p.orientation.y(), p.orientation.z(), p.orientation.w()}) {
        poses.push_back(float(q));
      }
    }
    j["movers"][std::size_t(m)]["poses_f32"] = encoded(poses);
  }
}

// Pursuer i and evader e at the sampled frames: the Apollonius sphere (centre and radius; a plane as radius
// -1 at the midpoint) and the pursuer's motion cone (axis and half-angle).
nlohmann::json pair_samples(const game::Trace& trace, int i, int e, double vp, double ve,
                            const std::vector<std::uint32_t>& samples) {
  std::vector<float> sphere, cone;
  sphere.reserve(samples.size() * 4);
  cone.reserve(samples.size() * 4);
  for (std::uint32_t k : samples) {
    const Vec3& p = trace.at(int(k), i).state.position;
    const Vec3& x = trace.at(int(k), e).state.position;
    if (ve <= 0.0) {  // a motionless evader: the surface shrinks to the evader itself
      push(sphere, x);
      sphere.push_back(0.0f);
    } else {
      const ApolloniusSurface s(p, x, ve / vp);
      push(sphere, s.is_plane() ? Vec3((p + x) / 2.0) : s.sphere().center);
      sphere.push_back(s.is_plane() ? -1.0f : float(s.sphere().radius));
    }
    const Vec3 pe = x - p;
    push(cone, pe.norm() > 0.0 ? Vec3(pe.normalized()) : Vec3::UnitX());
    cone.push_back(float(pursuer_cone_half_angle(vp, ve)));
  }
  return {{"pursuer", i}, {"evader", e}, {"apollonius_f32", encoded(sphere)}, {"cone_f32", encoded(cone)}};
}

// The trace's collisions and captures, each at its frame.
void trace_events(nlohmann::json& j, const game::Trace& trace) {
  const int frames = trace.frame_count();
  j["collisions"] = nlohmann::json::array();
  for (const game::CollisionEvent& c : trace.collisions) {
    j["collisions"].push_back({{"frame", std::min(c.step, frames - 1)},
                               {"time", c.time},
                               {"agent", c.agent},
                               {"kind", world::to_string(c.kind)},
                               {"point", vec(c.point)}});
  }
  j["captures"] = nlohmann::json::array();
  for (const game::CaptureEvent& c : trace.captures) {
    j["captures"].push_back({{"frame", std::min(c.step, frames - 1)}, {"time", c.time}, {"pursuer", c.pursuer}, {"evader", c.evader}});
  }
}

}  // namespace

nlohmann::json replay_json(const ReplayScene& scene, const game::Sim& sim, const game::Trace& trace,
                           const ReplayInfo& info) {
  const game::GameConfig& config = sim.config();
  const int frames = trace.frame_count(), n = trace.agents;
  assert(frames >= 1);
  nlohmann::json j = scene.json();
  j["title"] = info.title;
  j["subtitle"] = info.subtitle;
  j["capture_distance"] = config.capture_distance;
  j["dt"] = config.dt;
  j["frames"] = frames;
  j["times_f64"] = encoded(trace.times);

  // Every recorded frame of every agent.
  std::vector<double> speeds(std::size_t(n), 0.0);
  j["agents"] = nlohmann::json::array();
  for (int i = 0, pursuers = 0, evaders = 0; i < n; ++i) {
    const game::Role role = trace.roles[std::size_t(i)];
    const int rank = role == game::Role::kPursuer ? pursuers++ : evaders++;
    const game::AgentConfig& a = config.agent(role, rank);
    speeds[std::size_t(i)] = a.speed;
    j["agents"].push_back({{"name", game::agent_label(trace, i)},
                           {"role", game::to_string(role)},
                           {"radius", a.radius},
                           {"speed", a.speed},
                           {"track", agent_track(trace, i)}});
    // Each sensor's layer under its name (sense::Sensor::replay), from the readings the trace recorded; a
    // detector's also shows the knowledge it gave, which every trace records (a trajectory file's too).
    const auto sensors = sim.sensors(role, rank);
    for (int k = 0; k < int(sensors.size()); ++k) {
      const sense::Sensor& sensor = *sensors[std::size_t(k)];
      const bool recorded = k < trace.sensors(i);
      if (!recorded && sensor.detection() == nullptr) continue;
      nlohmann::json layer = sensor.replay(recorded ? trace.slot_readings(i, k).view(frames) : sense::RecordedReadings{frames, 0, {}, {}, {}});
      if (layer.is_null()) continue;
      if (sensor.detection() != nullptr) add_knowledge(layer, trace, i);
      j["agents"].back()[std::string(sensor.name())] = std::move(layer);
    }
    if (a.map.enabled && trace.sensors(i) > 0) j["agents"].back()["map"] = agent_map(trace, i, a.map.resolution);
  }

  // What the trace does not hold, sampled: where the movers are, and each pair's Apollonius sphere and cone.
  const std::vector<std::uint32_t> samples = sample_frames(frames, scene.settings().max_pose_samples);
  j["pose_frames_u32"] = encoded(samples);
  if (const world::MoverTimeline* movers = sim.movers()) mover_poses(j, *movers, trace, samples);
  j["pairs"] = nlohmann::json::array();
  for (int i = 0; i < n; ++i) {
    if (trace.roles[std::size_t(i)] != game::Role::kPursuer) continue;
    for (int e = 0; e < n; ++e) {
      if (trace.roles[std::size_t(e)] != game::Role::kEvader) continue;
      j["pairs"].push_back(pair_samples(trace, i, e, speeds[std::size_t(i)], speeds[std::size_t(e)], samples));
    }
  }
  trace_events(j, trace);
  return j;
}

}  // namespace peg3d::view
