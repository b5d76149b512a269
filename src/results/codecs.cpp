#include "results/codecs.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "core/base64.hpp"
#include "core/input_files.hpp"
#include "players/policy_io.hpp"

namespace peg3d::results {
namespace {

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

int int_from(const nlohmann::json& j) { return j.get<int>(); }

/// An enumeration stored as its value, checked against the largest one.
template <class E>
E enum_from(const nlohmann::json& j, int largest, const char* what) {
  const int v = j.get<int>();
  require(v >= 0 && v <= largest, what);
  return static_cast<E>(v);
}

Vec3 vec_from(const nlohmann::json& j, std::size_t at) {
  return {number_from_json(j.at(at)), number_from_json(j.at(at + 1)), number_from_json(j.at(at + 2))};
}

const nlohmann::json& array_of(const nlohmann::json& j, std::size_t size, const char* what) {
  require(j.is_array() && j.size() == size, what);
  return j;
}

nlohmann::json collision_to_json(const game::CollisionEvent& c) {
  return nlohmann::json::array({c.step, number_to_json(c.time), c.agent, static_cast<int>(c.role),
                                static_cast<int>(c.kind), c.obstacle_id, c.triangle, number_to_json(c.point.x()),
                                number_to_json(c.point.y()), number_to_json(c.point.z()), number_to_json(c.normal.x()),
                                number_to_json(c.normal.y()), number_to_json(c.normal.z()), number_to_json(c.fraction),
                                number_to_json(c.penetration)});
}

game::CollisionEvent collision_from_json(const nlohmann::json& j) {
  array_of(j, 15, "a collision needs 15 values");
  game::CollisionEvent c;
  c.step = int_from(j[0]);
  c.time = number_from_json(j[1]);
  c.agent = int_from(j[2]);
  c.role = enum_from<game::Role>(j[3], 1, "a role is 0 (pursuer) or 1 (evader)");
  c.kind = enum_from<world::ObstacleKind>(j[4], static_cast<int>(world::ObstacleKind::kMover), "unknown obstacle kind");
  c.obstacle_id = int_from(j[5]);
  c.triangle = int_from(j[6]);
  c.point = vec_from(j, 7);
  c.normal = vec_from(j, 10);
  c.fraction = number_from_json(j[13]);
  c.penetration = number_from_json(j[14]);
  return c;
}

nlohmann::json capture_to_json(const game::CaptureEvent& c) {
  return nlohmann::json::array({c.step, number_to_json(c.time), c.pursuer, c.evader, number_to_json(c.distance)});
}

game::CaptureEvent capture_from_json(const nlohmann::json& j) {
  array_of(j, 5, "a capture needs 5 values");
  return {int_from(j[0]), number_from_json(j[1]), int_from(j[2]), int_from(j[3]), number_from_json(j[4])};
}

// One agent at one instant: position, heading, the whole percept, the command, reward and whether in play; with
// limited sight five more: the opponent, whether it was seen and where it was taken to be.
constexpr std::size_t kFrameValues = 20, kSightFrameValues = 25;

nlohmann::json frame_to_json(const game::AgentFrame& f) {
  const game::Percept& q = f.percept;
  nlohmann::json j = nlohmann::json::array(
      {number_to_json(f.state.position.x()), number_to_json(f.state.position.y()), number_to_json(f.state.position.z()),
       number_to_json(f.state.heading.alpha), number_to_json(f.state.heading.theta), number_to_json(q.target_distance),
       number_to_json(q.target.azimuth), number_to_json(q.target.elevation), number_to_json(q.obstacle.distance),
       number_to_json(q.obstacle.point.x()), number_to_json(q.obstacle.point.y()), number_to_json(q.obstacle.point.z()),
       static_cast<int>(q.obstacle.found), number_to_json(q.to_obstacle.azimuth), number_to_json(q.to_obstacle.elevation),
       static_cast<int>(q.pinned), number_to_json(f.command.d_alpha), number_to_json(f.command.d_theta),
       number_to_json(f.reward), static_cast<int>(f.active)});
  if (f.opponent >= 0) {
    for (const nlohmann::json& v : {nlohmann::json(f.opponent), nlohmann::json(static_cast<int>(f.sees)),
                                    number_to_json(f.estimate.x()), number_to_json(f.estimate.y()),
                                    number_to_json(f.estimate.z())}) {
      j.push_back(v);
    }
  }
  return j;
}

game::AgentFrame frame_from_json(const nlohmann::json& j) {
  if (!(j.is_array() && j.size() == kSightFrameValues)) array_of(j, kFrameValues, "a trace frame needs 20 values (25 with sight)");
  game::AgentFrame f;
  f.state.position = vec_from(j, 0);
  f.state.heading = {number_from_json(j[3]), number_from_json(j[4])};
  game::Percept& q = f.percept;
  q.target_distance = number_from_json(j[5]);
  q.target = {number_from_json(j[6]), number_from_json(j[7])};
  q.obstacle.distance = number_from_json(j[8]);
  q.obstacle.point = vec_from(j, 9);
  q.obstacle.found = int_from(j[12]) != 0;
  q.to_obstacle = {number_from_json(j[13]), number_from_json(j[14])};
  q.pinned = int_from(j[15]) != 0;
  f.command = {number_from_json(j[16]), number_from_json(j[17])};
  f.reward = number_from_json(j[18]);
  f.active = int_from(j[19]) != 0;
  if (j.size() == kSightFrameValues) {
    f.opponent = int_from(j[20]);
    f.sees = int_from(j[21]) != 0;
    f.estimate = vec_from(j, 22);
  }
  return f;
}

}  // namespace

nlohmann::json number_to_json(double v) {
  if (std::isfinite(v)) return v;
  if (std::isnan(v)) return std::signbit(v) ? "-nan" : "nan";
  return v > 0.0 ? "inf" : "-inf";
}

double number_from_json(const nlohmann::json& j) {
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    constexpr double kInf = std::numeric_limits<double>::infinity();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "-nan") return -std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return kInf;
    if (s == "-inf") return -kInf;
  }
  throw std::invalid_argument("expected a number, got " + brief(j));
}

nlohmann::json episode_to_json(const game::EpisodeResult& e) {
  return nlohmann::json::array(
      {static_cast<int>(e.outcome), e.steps, number_to_json(e.duration), number_to_json(e.final_distance),
       number_to_json(e.pursuer_path), number_to_json(e.evader_path), e.collisions,
       e.first_collision ? collision_to_json(*e.first_collision) : nlohmann::json(nullptr),
       number_to_json(e.pursuer_return), number_to_json(e.evader_return), e.pursuer_pinned_steps,
       e.evader_pinned_steps, e.pursuer_agent_steps, e.evader_agent_steps, e.pursuers, e.evaders, e.captures,
       number_to_json(e.capture_time_sum), number_to_json(e.last_capture_time)});
}

game::EpisodeResult episode_from_json(const nlohmann::json& j) {
  array_of(j, 19, "an episode needs 19 values");
  game::EpisodeResult e;
  e.outcome = enum_from<game::Outcome>(j[0], static_cast<int>(game::Outcome::kEvaderCollision), "unknown outcome");
  e.steps = int_from(j[1]);
  e.duration = number_from_json(j[2]);
  e.final_distance = number_from_json(j[3]);
  e.pursuer_path = number_from_json(j[4]);
  e.evader_path = number_from_json(j[5]);
  e.collisions = int_from(j[6]);
  if (!j[7].is_null()) e.first_collision = collision_from_json(j[7]);
  e.pursuer_return = number_from_json(j[8]);
  e.evader_return = number_from_json(j[9]);
  e.pursuer_pinned_steps = int_from(j[10]);
  e.evader_pinned_steps = int_from(j[11]);
  e.pursuer_agent_steps = int_from(j[12]);
  e.evader_agent_steps = int_from(j[13]);
  e.pursuers = int_from(j[14]);
  e.evaders = int_from(j[15]);
  e.captures = int_from(j[16]);
  e.capture_time_sum = number_from_json(j[17]);
  e.last_capture_time = number_from_json(j[18]);
  return e;
}

nlohmann::json episodes_to_json(const std::vector<game::EpisodeResult>& episodes) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : episodes) out.push_back(episode_to_json(e));
  return out;
}

std::vector<game::EpisodeResult> episodes_from_json(const nlohmann::json& j) {
  require(j.is_array(), "expected a list of episodes");
  std::vector<game::EpisodeResult> out;
  out.reserve(j.size());
  for (const auto& e : j) out.push_back(episode_from_json(e));
  return out;
}

nlohmann::json agent_summary_to_json(const game::AgentSummary& a) {
  return nlohmann::json::array({static_cast<int>(a.role), a.rank, number_to_json(a.path), number_to_json(a.total_reward),
                                a.steps, number_to_json(a.pinned_fraction), a.collisions, a.captures,
                                number_to_json(a.captured_at)});
}

game::AgentSummary agent_summary_from_json(const nlohmann::json& j) {
  array_of(j, 9, "an agent summary needs 9 values");
  game::AgentSummary a;
  a.role = enum_from<game::Role>(j[0], 1, "a role is 0 (pursuer) or 1 (evader)");
  a.rank = int_from(j[1]);
  a.path = number_from_json(j[2]);
  a.total_reward = number_from_json(j[3]);
  a.steps = int_from(j[4]);
  a.pinned_fraction = number_from_json(j[5]);
  a.collisions = int_from(j[6]);
  a.captures = int_from(j[7]);
  a.captured_at = number_from_json(j[8]);
  return a;
}

namespace {

// A trace's sensing, checked to fit its frames and agents before anything indexes it.
void sensing_from_json(const nlohmann::json& j, game::Trace& t) {
  t.slot_first = j.at("slot_first").get<std::vector<int>>();
  t.value_first = j.at("value_first").get<std::vector<int>>();
  require(t.slot_first.size() == std::size_t(t.agents) + 1 && t.slot_first.front() == 0 &&
              std::is_sorted(t.slot_first.begin(), t.slot_first.end()),
          "a trace's sensor slots are one list per agent");
  const auto slots = std::size_t(t.slot_first.back());
  require(t.value_first.size() == slots + 1 && t.value_first.front() == 0 &&
              std::is_sorted(t.value_first.begin(), t.value_first.end()),
          "a trace's sensor values are one range per slot");
  const std::vector<std::uint8_t> bytes = base64_decode(j.at("readings_f32").get<std::string>());
  const std::size_t frames = t.times.size(), values = std::size_t(t.value_first.back());
  require(bytes.size() == frames * values * sizeof(float), "a trace's readings are one value per frame and slot value");
  t.readings.resize(frames * values);
  std::memcpy(t.readings.data(), bytes.data(), bytes.size());
  t.echoes = base64_decode(j.at("echo_u8").get<std::string>());
  require(t.echoes.size() == frames * values, "a trace's echoes are one per reading");
  t.scan_frames = j.at("scan_frames").get<std::vector<int>>();
  require(t.scan_frames.size() == frames * slots, "a trace's scan frames are one per frame and slot");
  for (const auto& f : j.at("map_flips")) {
    array_of(f, 6, "a map flip needs 6 values");
    game::MapFlip m{int_from(f[0]), int_from(f[1]), vec_from(f, 2), int_from(f[5]) != 0};
    require(m.agent >= 0 && m.agent < t.agents && m.frame >= 0 && std::size_t(m.frame) < frames, "a map flip of no frame or agent");
    t.map_flips.push_back(m);
  }
}

}  // namespace

nlohmann::json trace_to_json(const game::Trace& t) {
  nlohmann::json roles = nlohmann::json::array(), times = nlohmann::json::array(), frames = nlohmann::json::array(),
                 collisions = nlohmann::json::array(), captures = nlohmann::json::array();
  for (const game::Role r : t.roles) roles.push_back(static_cast<int>(r));
  for (const double v : t.times) times.push_back(number_to_json(v));
  for (const game::AgentFrame& f : t.frames) frames.push_back(frame_to_json(f));
  for (const auto& c : t.collisions) collisions.push_back(collision_to_json(c));
  for (const auto& c : t.captures) captures.push_back(capture_to_json(c));
  nlohmann::json j{{"agents", t.agents}, {"roles", std::move(roles)},           {"times", std::move(times)},
                   {"frames", std::move(frames)}, {"collisions", std::move(collisions)}, {"captures", std::move(captures)}};
  if (!t.slot_first.empty()) {
    // The sensors' readings as their float bits (base64 of little-endian bytes) and the maps' changes: what a
    // replay's sensor layers are drawn from.
    nlohmann::json flips = nlohmann::json::array();
    for (const game::MapFlip& f : t.map_flips) {
      flips.push_back({f.frame, f.agent, number_to_json(f.centre.x()), number_to_json(f.centre.y()),
                       number_to_json(f.centre.z()), static_cast<int>(f.occupied)});
    }
    j["sensing"] = {{"slot_first", t.slot_first},
                    {"value_first", t.value_first},
                    {"readings_f32", base64(t.readings.data(), t.readings.size() * sizeof(float))},
                    {"echo_u8", base64(t.echoes.data(), t.echoes.size())},
                    {"scan_frames", t.scan_frames},
                    {"map_flips", std::move(flips)}};
  }
  return j;
}

game::Trace trace_from_json(const nlohmann::json& j) {
  game::Trace t;
  t.agents = int_from(j.at("agents"));
  require(t.agents >= 0, "a trace's agent count is >= 0");
  const auto& roles = array_of(j.at("roles"), static_cast<std::size_t>(t.agents), "a trace needs one role per agent");
  for (const auto& r : roles) t.roles.push_back(enum_from<game::Role>(r, 1, "a role is 0 (pursuer) or 1 (evader)"));
  require(j.at("times").is_array(), "a trace's times are a list");
  for (const auto& v : j.at("times")) t.times.push_back(number_from_json(v));
  array_of(j.at("frames"), t.times.size() * static_cast<std::size_t>(t.agents), "a trace needs one frame per time and agent");
  t.frames.reserve(j.at("frames").size());
  for (const auto& f : j.at("frames")) t.frames.push_back(frame_from_json(f));
  require(j.at("collisions").is_array() && j.at("captures").is_array(), "a trace's events are lists");
  for (const auto& c : j.at("collisions")) t.collisions.push_back(collision_from_json(c));
  for (const auto& c : j.at("captures")) t.captures.push_back(capture_from_json(c));
  if (const auto it = j.find("sensing"); it != j.end()) sensing_from_json(*it, t);
  return t;
}

nlohmann::json role_models_to_json(const players::RoleModels& m) {
  nlohmann::json models = nlohmann::json::array();
  for (const auto& model : m.models) models.push_back(players::policy_to_json(*model));
  return {{"models", std::move(models)}, {"of_agent", m.of_agent}};
}

players::RoleModels role_models_from_json(const nlohmann::json& j, game::Role role) {
  players::RoleModels m;
  require(j.at("models").is_array(), "a role's models are a list");
  for (const auto& doc : j.at("models")) m.models.push_back(players::policy_from_json(doc, {}, role));
  m.of_agent = j.at("of_agent").get<std::vector<int>>();
  for (const int k : m.of_agent) require(k >= -1 && k < static_cast<int>(m.models.size()), "a model index out of range");
  return m;
}

}  // namespace peg3d::results
