#include "game/game_config.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/validation.hpp"
#include "geometry/angles.hpp"

namespace peg3d::game {
namespace {

// Enum <-> string tables. Unknown strings are errors (nlohmann's enum macro would silently pick the first).
template <typename E, std::size_t N>
using Names = std::array<std::pair<E, const char*>, N>;

constexpr Names<AngleInputs, 2> kAngleInputs{{{AngleInputs::kAzimuth, "azimuth"},
                                              {AngleInputs::kAzimuthElevation, "azimuth-elevation"}}};
constexpr Names<EvaderReference, 2> kEvaderReference{{{EvaderReference::kTowardPursuer, "toward-pursuer"},
                                                      {EvaderReference::kAwayFromPursuer, "away-from-pursuer"}}};
constexpr Names<FaclStructure, 2> kStructure{{{FaclStructure::kJoint, "joint"}, {FaclStructure::kPerAngle, "per-angle"}}};
constexpr Names<RewardKind, 2> kRewardKind{{{RewardKind::kPotentialField, "potential-field"},
                                            {RewardKind::kDistanceOnly, "distance-only"}}};
constexpr Names<EvaderInversion, 2> kInversion{{{EvaderInversion::kNegate, "negate"}, {EvaderInversion::kMirror, "mirror"}}};
constexpr Names<CollisionMode, 2> kCollision{{{CollisionMode::kTerminate, "terminate"}, {CollisionMode::kPenalize, "penalize"}}};
constexpr Names<InitialHeading, 4> kInitialHeading{{{InitialHeading::kChase, "chase"},
                                                    {InitialHeading::kFacing, "facing"},
                                                    {InitialHeading::kPlusX, "plus-x"},
                                                    {InitialHeading::kRandom, "random"}}};
constexpr Names<SteeringReading, 2> kReading{{{SteeringReading::kPerStep, "per-step"},
                                              {SteeringReading::kPerSecond, "per-second"}}};

template <typename E, std::size_t N>
std::string enum_name(const Names<E, N>& names, E e) {
  for (const auto& [value, name] : names)
    if (value == e) return name;
  throw std::logic_error("enum value without a name");
}

template <typename E, std::size_t N>
E enum_value(const Names<E, N>& names, const nlohmann::json& j, const char* field) {
  const std::string s = j.get<std::string>();
  std::string valid;
  for (const auto& [value, name] : names) {
    if (s == name) return value;
    valid += valid.empty() ? name : std::string(", ") + name;
  }
  throw InvalidParameter(field, "\"" + s + "\"", "must be one of: " + valid);
}

// Reads j[key] into out when present, so a partial JSON object keeps the defaults of the rest.
template <typename T>
void read(const nlohmann::json& j, const char* key, T& out) {
  if (const auto it = j.find(key); it != j.end()) it->get_to(out);
}

template <typename E, std::size_t N>
void read_enum(const nlohmann::json& j, const char* key, const Names<E, N>& names, E& out, const char* field) {
  if (const auto it = j.find(key); it != j.end()) out = enum_value(names, *it, field);
}

void validate_agent(const AgentConfig& a, const std::string& p, Role role) {
  static constexpr std::array kPolicies{"facl", "pure-pursuit", "pn", "apollonius", "flee", "flee-apollonius", "random"};
  bool known = false;
  for (const char* k : kPolicies) known |= a.policy == k;
  if (!known) {
    throw InvalidParameter(p + ".policy", "\"" + a.policy + "\"",
                           "must be one of: facl, pure-pursuit, pn, apollonius, flee, flee-apollonius, random");
  }
  if (role == Role::kPursuer) {
    require_positive(p + ".speed", a.speed);
  } else {
    require_non_negative(p + ".speed", a.speed);
  }
  require_positive(p + ".radius", a.radius);
  a.steering.validate(p + ".steering");
  require_positive(p + ".observation.target_range", a.observation.target_range);
  require_positive(p + ".observation.obstacle_range", a.observation.obstacle_range);
  require_at_least(p + ".observation.sets", a.observation.sets, 2);
  const RewardConfig& r = a.reward;
  require_non_negative(p + ".reward.alpha_r", r.alpha_r);
  require_non_negative(p + ".reward.beta_a", r.beta_a);
  require_non_negative(p + ".reward.gamma_s", r.gamma_s);
  require_non_negative(p + ".reward.w_r", r.w_r);
  require_non_negative(p + ".reward.w_a", r.w_a);
  require_non_negative(p + ".reward.collision_penalty", r.collision_penalty);
  require_positive(p + ".pn_gain", a.pn_gain);
  require_positive(p + ".guard.stop_distance", a.guard.stop_distance);
  if (!(a.guard.warn_distance > a.guard.stop_distance)) {
    throw InvalidParameter(p + ".guard.warn_distance", format_value(a.guard.warn_distance), "must be > guard.stop_distance");
  }
  if (a.structure == FaclStructure::kPerAngle && a.observation.angles != AngleInputs::kAzimuthElevation) {
    throw InvalidParameter(p + ".structure", "\"per-angle\"", "needs observation.angles = azimuth-elevation");
  }
  a.facl.validate(p + ".facl");
}

}  // namespace

const char* to_string(Role r) { return r == Role::kPursuer ? "pursuer" : "evader"; }

int GameConfig::max_steps() const { return static_cast<int>(std::lround(time_limit / dt)); }

void GameConfig::validate() const {
  require_positive("dt", dt);
  require_positive("time_limit", time_limit);
  if (time_limit < dt) throw InvalidParameter("time_limit", format_value(time_limit), "must be >= dt");
  require_positive("capture_distance", capture_distance);
  validate_agent(pursuer, "pursuer", Role::kPursuer);
  validate_agent(evader, "evader", Role::kEvader);
}

AgentConfig agent_preset(const std::string& name, Role role) {
  AgentConfig a;
  a.speed = role == Role::kPursuer ? 1.1 : 1.0;
  if (name == "peg3d") {
    a.steering.polar_margin = kPi / 3;  // climb and dive limited to 30 degrees (docs/paper-notes.md)
    a.motion_space = role == Role::kPursuer;  // alpha1 >= pi/2 drives the evader into the walls
    return a;
  }
  if (name == "paper") {
    a.guard.enabled = false;
    a.observation.angles = AngleInputs::kAzimuth;
    a.observation.evader_reference = EvaderReference::kTowardPursuer;
    a.observation.boundary_is_obstacle = false;
    a.observation.obstacle_range = 35.0;
    a.structure = FaclStructure::kJoint;
    return a;
  }
  if (name == "baseline") {
    a.steering.polar_margin = kPi / 3;
    a.motion_space = false;
    a.reward.kind = RewardKind::kDistanceOnly;
    return a;
  }
  throw std::invalid_argument("unknown configuration '" + name + "' (valid: peg3d, paper, baseline)");
}

GameConfig preset(const std::string& name) {
  GameConfig c;
  c.pursuer = agent_preset(name, Role::kPursuer);
  // The baseline replaces the pursuer's method only; its opponent is peg3d's evader, so the two arms of a
  // comparison differ in one thing.
  c.evader = agent_preset(name == "baseline" ? "peg3d" : name, Role::kEvader);
  return c;
}

void to_json(nlohmann::json& j, const AgentConfig& a) {
  j = nlohmann::json{
      {"policy", a.policy},
      {"speed", a.speed},
      {"radius", a.radius},
      {"steering",
       {{"max_turn", a.steering.max_turn},
        {"reading", enum_name(kReading, a.steering.reading)},
        {"polar_margin", a.steering.polar_margin}}},
      {"motion_space", a.motion_space},
      {"guard",
       {{"enabled", a.guard.enabled}, {"stop_distance", a.guard.stop_distance}, {"warn_distance", a.guard.warn_distance}}},
      {"observation",
       {{"angles", enum_name(kAngleInputs, a.observation.angles)},
        {"evader_reference", enum_name(kEvaderReference, a.observation.evader_reference)},
        {"boundary_is_obstacle", a.observation.boundary_is_obstacle},
        {"target_range", a.observation.target_range},
        {"obstacle_range", a.observation.obstacle_range},
        {"sets", a.observation.sets}}},
      {"reward",
       {{"kind", enum_name(kRewardKind, a.reward.kind)},
        {"alpha_r", a.reward.alpha_r},
        {"beta_a", a.reward.beta_a},
        {"gamma_s", a.reward.gamma_s},
        {"w_r", a.reward.w_r},
        {"w_a", a.reward.w_a},
        {"inversion", enum_name(kInversion, a.reward.inversion)},
        {"collision_penalty", a.reward.collision_penalty}}},
      {"facl",
       {{"actor_rate", a.facl.actor_rate},
        {"critic_rate", a.facl.critic_rate},
        {"discount", a.facl.discount},
        {"exploration_variance", a.facl.exploration_variance},
        {"initial_actor", a.facl.initial_actor},
        {"initial_critic", a.facl.initial_critic}}},
      {"structure", enum_name(kStructure, a.structure)},
      {"pn_gain", a.pn_gain},
  };
}

void from_json(const nlohmann::json& j, AgentConfig& a) {
  read(j, "policy", a.policy);
  read(j, "speed", a.speed);
  read(j, "radius", a.radius);
  if (const auto s = j.find("steering"); s != j.end()) {
    read(*s, "max_turn", a.steering.max_turn);
    read_enum(*s, "reading", kReading, a.steering.reading, "steering.reading");
    read(*s, "polar_margin", a.steering.polar_margin);
  }
  read(j, "motion_space", a.motion_space);
  if (const auto g = j.find("guard"); g != j.end()) {
    read(*g, "enabled", a.guard.enabled);
    read(*g, "stop_distance", a.guard.stop_distance);
    read(*g, "warn_distance", a.guard.warn_distance);
  }
  if (const auto o = j.find("observation"); o != j.end()) {
    read_enum(*o, "angles", kAngleInputs, a.observation.angles, "observation.angles");
    read_enum(*o, "evader_reference", kEvaderReference, a.observation.evader_reference, "observation.evader_reference");
    read(*o, "boundary_is_obstacle", a.observation.boundary_is_obstacle);
    read(*o, "target_range", a.observation.target_range);
    read(*o, "obstacle_range", a.observation.obstacle_range);
    read(*o, "sets", a.observation.sets);
  }
  if (const auto r = j.find("reward"); r != j.end()) {
    read_enum(*r, "kind", kRewardKind, a.reward.kind, "reward.kind");
    read(*r, "alpha_r", a.reward.alpha_r);
    read(*r, "beta_a", a.reward.beta_a);
    read(*r, "gamma_s", a.reward.gamma_s);
    read(*r, "w_r", a.reward.w_r);
    read(*r, "w_a", a.reward.w_a);
    read_enum(*r, "inversion", kInversion, a.reward.inversion, "reward.inversion");
    read(*r, "collision_penalty", a.reward.collision_penalty);
  }
  if (const auto f = j.find("facl"); f != j.end()) {
    read(*f, "actor_rate", a.facl.actor_rate);
    read(*f, "critic_rate", a.facl.critic_rate);
    read(*f, "discount", a.facl.discount);
    read(*f, "exploration_variance", a.facl.exploration_variance);
    read(*f, "initial_actor", a.facl.initial_actor);
    read(*f, "initial_critic", a.facl.initial_critic);
  }
  read_enum(j, "structure", kStructure, a.structure, "structure");
  read(j, "pn_gain", a.pn_gain);
}

void to_json(nlohmann::json& j, const GameConfig& c) {
  j = nlohmann::json{{"dt", c.dt},
                     {"time_limit", c.time_limit},
                     {"capture_distance", c.capture_distance},
                     {"collision", enum_name(kCollision, c.collision)},
                     {"initial_heading", enum_name(kInitialHeading, c.initial_heading)},
                     {"pursuer", c.pursuer},
                     {"evader", c.evader}};
}

void from_json(const nlohmann::json& j, GameConfig& c) {
  read(j, "dt", c.dt);
  read(j, "time_limit", c.time_limit);
  read(j, "capture_distance", c.capture_distance);
  read_enum(j, "collision", kCollision, c.collision, "collision");
  read_enum(j, "initial_heading", kInitialHeading, c.initial_heading, "initial_heading");
  read(j, "pursuer", c.pursuer);
  read(j, "evader", c.evader);
}

}  // namespace peg3d::game
