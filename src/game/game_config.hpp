#pragma once
// Configuration of a pursuit-evasion game: timing, termination, how moving obstacles are sensed and move, and
// the agents (game/agent_config.hpp) and teams (game/teams.hpp) it composes. Every struct lists its fields once,
// with unit, valid range and meaning, in a visit_fields() table (core/config_fields.hpp) that drives validation,
// JSON in and out, `--set` and `--list-config`. Named presets give the paper's configuration, peg3d's default and
// the baseline (docs/paper-notes.md explains each difference).

#include <concepts>
#include <string>
#include <type_traits>
#include <vector>

#include "core/config_fields.hpp"
#include "game/agent_config.hpp"
#include "game/teams.hpp"

namespace peg3d::game {



enum class CollisionMode {
  kTerminate,  ///< a collision ends the episode (no capture)
  kPenalize,   ///< the agent stops at the contact, receives the penalty, and the episode goes on
};
inline constexpr config::EnumNames<CollisionMode, 2> kCollisionModeNames{
    {{CollisionMode::kTerminate, "terminate"}, {CollisionMode::kPenalize, "penalize"}}};

/// Initial headings when the map's scenario gives none.
enum class InitialHeading {
  kChase,   ///< level; each pursuer faces its nearest evader, each evader faces directly away from its nearest pursuer
  kFacing,  ///< level; each agent faces its nearest opponent
  kPlusX,   ///< level, along +x
  kRandom,  ///< uniformly random directions (from the run's seed)
};
inline constexpr config::EnumNames<InitialHeading, 4> kInitialHeadingNames{{{InitialHeading::kChase, "chase"},
                                                                            {InitialHeading::kFacing, "facing"},
                                                                            {InitialHeading::kPlusX, "plus-x"},
                                                                            {InitialHeading::kRandom, "random"}}};

/// How agents sense moving obstacles (docs/maps.md compares the two).
enum class MoverSensing {
  kExact,   ///< the static distance field, and each mover's exact distance at the current time (the default)
  kOctree,  ///< an octree with the movers' voxels marked and dynamicEDT3D updated incrementally every step
};
inline constexpr config::EnumNames<MoverSensing, 2> kMoverSensingNames{
    {{MoverSensing::kExact, "exact"}, {MoverSensing::kOctree, "octree"}}};

/// How the map's dynamic bodies move (docs/maps.md compares the two).
enum class MoverDynamics {
  kShared,  ///< simulated once per map without the agents, shared by every run; a touch is a collision (the default)
  kPush,    ///< every run simulates them with the agents as kinematic bodies, which push the pushable ones
};
inline constexpr config::EnumNames<MoverDynamics, 2> kMoverDynamicsNames{
    {{MoverDynamics::kShared, "shared"}, {MoverDynamics::kPush, "push"}}};


struct GameConfig {
  double dt = 0.1;                ///< s, sample time, > 0 (paper 0.1)
  double time_limit = 100.0;      ///< s, episode limit, >= dt (paper 100)
  double capture_distance = 1.0;  ///< m, d_s, > 0 (paper 1)
  CollisionMode collision = CollisionMode::kTerminate;
  InitialHeading initial_heading = InitialHeading::kChase;
  MoverSensing mover_sensing = MoverSensing::kExact;
  MoverDynamics mover_dynamics = MoverDynamics::kShared;
  AgentConfig pursuer;  ///< every pursuer without an entry in `pursuers`
  AgentConfig evader;   ///< every evader without an entry in `evaders`
  /// Per-agent settings: the k-th pursuer of a scenario plays pursuers[k] when the list has it. In a
  /// configuration file an entry starts from `pursuer` and changes what it lists.
  std::vector<AgentConfig> pursuers;
  std::vector<AgentConfig> evaders;  ///< likewise for evaders, starting from `evader`
  TeamConfig team;

  int max_steps() const;  ///< time_limit / dt, rounded
  /// The configuration of the k-th agent (k >= 0) of a role.
  const AgentConfig& agent(Role r, int k = 0) const {
    const auto& list = r == Role::kPursuer ? pursuers : evaders;
    return k < static_cast<int>(list.size()) ? list[static_cast<std::size_t>(k)] : (r == Role::kPursuer ? pursuer : evader);
  }
  /// Gives the k-th agent (k >= 0) of a role its own configuration; agents before it without an entry of their
  /// own get one equal to the role's default, so they play as before.
  void set_agent(Role r, int k, const AgentConfig& a);
  /// The configuration of agent i of a game's order, `pursuers` pursuers first and then the evaders.
  const AgentConfig& agent_at(int i, int pursuers) const { return agent(role_at(i, pursuers), rank_at(i, pursuers)); }
  /// Throws InvalidParameter naming the dotted field.
  void validate() const;
  bool operator==(const GameConfig&) const = default;
};

/// The configuration a scripted player plays with: the base agent's kinematics and guard, its own policy (a
/// player's name), no motion space and no learning.
AgentConfig scripted_agent(const AgentConfig& base, const std::string& policy);
/// `config` with every agent of `role` (its default and each per-agent entry) playing the scripted `policy`.
GameConfig with_role_playing(GameConfig config, Role role, const std::string& policy);

/// The preset names: "peg3d" (the default), "paper" (as faithful as the text allows), "baseline" (FACL in
/// the manner of Al-Mahbashi et al. 2020 for the pursuer) and "robust" (peg3d's agents tuned to hold up against
/// classic opponents; the experiments train it with an opponent pool: experiment/trial_config.hpp,
/// docs/learning.md).
inline constexpr const char* kPresetNames[] = {"peg3d", "paper", "baseline", "robust"};
/// kPresetNames as text for messages and help: "peg3d, paper, baseline, robust".
std::string preset_list();
/// A named configuration of the game (how a preset trains is experiment::trial_preset's). Throws InvalidParameter
/// for an unknown name.
GameConfig preset(const std::string& name);
/// The preset's settings for one agent (the pursuer's or the evader's side of that preset).
AgentConfig agent_preset(const std::string& name, Role role);


// ---- Field tables (core/config_fields.hpp) ----


namespace detail {
/// The role rules of one agent's settings: a pursuer moves. (Whether its policy plays the role is the players'
/// registry's check, players::check_players.)
template <class V>
void require_role(V& v, const AgentConfig& a, Role role, const std::string& prefix) {
  if (role == Role::kPursuer) v.require(a.speed > 0.0, prefix + ".speed", a.speed, "must be > 0 for a pursuer");
}
}  // namespace detail

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, GameConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.number("dt", c.dt, Range::positive(), "s", "sample time (paper 0.1)");
  v.number("time_limit", c.time_limit, Range::positive(), "s", "episode limit (paper 100)");
  v.number("capture_distance", c.capture_distance, Range::positive(), "m", "d_s: capture at d_PE <= d_s (paper 1)");
  v.choice("collision", c.collision, kCollisionModeNames, "whether hitting an obstacle ends the episode");
  v.choice("initial_heading", c.initial_heading, kInitialHeadingNames, "headings of starts that give none");
  v.choice("mover_sensing", c.mover_sensing, kMoverSensingNames,
           "how agents sense moving obstacles: exact distances beside the static field, or an incrementally updated "
           "octree EDT (rebuilt at every reset: slow)");
  v.choice("mover_dynamics", c.mover_dynamics, kMoverDynamicsNames,
           "how dynamic bodies move: simulated once per map without the agents (shared), or in every run with the "
           "agents pushing the pushable ones (push: costs a Bullet world per run; needs mover_sensing exact)");
  v.section("pursuer", c.pursuer, "every pursuer without its own entry in pursuers");
  v.section("evader", c.evader, "every evader without its own entry in evaders");
  v.sections("pursuers", c.pursuers, c.pursuer, "per-pursuer settings, by index in the scenario");
  v.sections("evaders", c.evaders, c.evader, "per-evader settings, by index in the scenario");
  v.section("team", c.team, "how teams play");
  v.require(c.time_limit >= c.dt, "time_limit", c.time_limit, "must be >= dt");
  v.require(c.time_limit / c.dt <= 1e8, "time_limit", c.time_limit, "must be at most 1e8 steps of dt");
  detail::require_role(v, c.pursuer, Role::kPursuer, "pursuer");
  detail::require_role(v, c.evader, Role::kEvader, "evader");
  for (std::size_t k = 0; k < c.pursuers.size(); ++k)
    detail::require_role(v, c.pursuers[k], Role::kPursuer, "pursuers." + std::to_string(k));
  for (std::size_t k = 0; k < c.evaders.size(); ++k)
    detail::require_role(v, c.evaders[k], Role::kEvader, "evaders." + std::to_string(k));
}

}  // namespace peg3d::game
