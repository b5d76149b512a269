#pragma once
// Configuration of one pursuit-evasion game: timing, termination, and per agent its kinematics, policy,
// observation, reward and learner. Every field has a default, a unit and a valid range; validate() throws
// InvalidParameter naming the dotted field. Named presets give the paper's configuration, peg3d's default
// and the baseline (docs/paper-notes.md explains each difference).

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "fuzzy/facl_learner.hpp"
#include "geometry/kinematics.hpp"

namespace peg3d::game {

enum class Role { kPursuer, kEvader };

/// Which angle errors the observation carries.
enum class AngleInputs {
  kAzimuth,           ///< paper: one signed azimuth error per direction (target, obstacle)
  kAzimuthElevation,  ///< a signed azimuth and a signed elevation error per direction
};

/// The line the evader's target angle is measured from.
enum class EvaderReference {
  kTowardPursuer,    ///< paper eq. (20): from E->P, so fleeing straight away reads +-pi (the wrap point)
  kAwayFromPursuer,  ///< from P->E, so fleeing straight away reads 0
};

/// How FACL turns observations into the two steering angles.
enum class FaclStructure {
  kJoint,     ///< one actor-critic over all inputs with two outputs (the paper)
  kPerAngle,  ///< one actor-critic per steering angle, each over d_PE, its target error, d_O and its obstacle error
};

enum class RewardKind {
  kPotentialField,  ///< paper eq. (15)-(18): w_r r_O + w_a r_PE + r_s
  kDistanceOnly,    ///< baseline: the normalised change of d_PE, (d(t) - d(t+1)) / ((vP + vE) dt)
};

/// How the paper's "inverted" terms are read for the evader.
enum class EvaderInversion {
  kNegate,  ///< r_E = -r_P term by term: 1 - exp(-beta dd), -gamma_s g (the repulsion form)
  kMirror,  ///< the sign of the argument flips: exp(beta dd) - 1, -gamma_s g
};

enum class CollisionMode {
  kTerminate,  ///< a collision ends the episode (no capture)
  kPenalize,   ///< the agent stops at the contact, receives the penalty, and the episode goes on
};

/// Initial headings when the map's scenario gives none.
enum class InitialHeading {
  kChase,   ///< level; the pursuer faces the evader, the evader faces directly away
  kFacing,  ///< level; each faces the other
  kPlusX,   ///< level, both along +x
  kRandom,  ///< uniformly random directions (from the run's seed)
};

struct ObservationConfig {
  AngleInputs angles = AngleInputs::kAzimuthElevation;
  EvaderReference evader_reference = EvaderReference::kAwayFromPursuer;
  bool boundary_is_obstacle = true;  ///< floor, ceiling and walls count in d_O, its direction and r_O
  double target_range = 35.0;        ///< m, d_PE partition [0, target_range], > 0 (paper 35)
  double obstacle_range = 5.0;       ///< m, d_O partition [0, obstacle_range], > 0 (paper 35)
  int sets = 5;                      ///< triangular sets per input, >= 2 (paper 5)
};

struct RewardConfig {
  RewardKind kind = RewardKind::kPotentialField;
  double alpha_r = 10.0;  ///< repulsion coefficient (1/m), >= 0 (paper 10)
  double beta_a = 5.0;    ///< attraction coefficient (1/m), >= 0 (paper 5)
  double gamma_s = 20.0;  ///< capture reward, >= 0 (paper 20)
  double w_r = 5.0;       ///< repulsion weight, >= 0 (paper 5)
  double w_a = 10.0;      ///< attraction weight, >= 0 (paper 10)
  EvaderInversion inversion = EvaderInversion::kNegate;
  double collision_penalty = 0.0;  ///< subtracted from the colliding agent's reward, >= 0 (paper: none)
};

/// A safety layer on top of any policy: near an obstacle of the map (not the arena boundary), headings that
/// approach it are excluded, like the motion space excludes headings that lose ground. Within
/// `stop_distance` of the obstacle the heading may not approach it at all; between `stop_distance` and
/// `warn_distance` the excluded cone about the direction to the obstacle narrows linearly to nothing.
struct ObstacleGuard {
  bool enabled = true;
  double stop_distance = 0.8;  ///< m, > 0; covers radius + one step + the distance field's voxel error
  double warn_distance = 2.0;  ///< m, > stop_distance
};

/// One agent: who drives it and how it moves, senses, is rewarded and learns.
struct AgentConfig {
  /// facl | pure-pursuit | pn | apollonius | flee | flee-apollonius | random
  std::string policy = "facl";
  double speed = 1.0;    ///< m/s; pursuer > 0, evader >= 0 (0: a motionless target); paper 1.1 and 1.0
  double radius = 0.25;  ///< m, collision sphere, > 0
  SteeringConfig steering;
  bool motion_space = true;  ///< keep the heading in the paper's optimal motion space (section 3.1)
  ObstacleGuard guard;
  ObservationConfig observation;
  RewardConfig reward;
  fuzzy::FaclConfig facl;
  FaclStructure structure = FaclStructure::kPerAngle;
  double pn_gain = 3.0;  ///< proportional-navigation constant N, > 0
};

struct GameConfig {
  double dt = 0.1;                ///< s, sample time, > 0 (paper 0.1)
  double time_limit = 100.0;      ///< s, episode limit, >= dt (paper 100)
  double capture_distance = 1.0;  ///< m, d_s, > 0 (paper 1)
  CollisionMode collision = CollisionMode::kTerminate;
  InitialHeading initial_heading = InitialHeading::kChase;
  AgentConfig pursuer;
  AgentConfig evader;

  int max_steps() const;  ///< time_limit / dt, rounded
  const AgentConfig& agent(Role r) const { return r == Role::kPursuer ? pursuer : evader; }
  void validate() const;
};

/// Named configurations: "peg3d" (the default), "paper" (as faithful as the text allows) and "baseline"
/// (FACL in the manner of Al-Mahbashi et al. 2020 for the pursuer). Throws std::invalid_argument for
/// an unknown name.
GameConfig preset(const std::string& name);
/// The preset's settings for one agent (the pursuer's or the evader's side of that preset).
AgentConfig agent_preset(const std::string& name, Role role);

const char* to_string(Role r);

void to_json(nlohmann::json& j, const GameConfig& c);
void from_json(const nlohmann::json& j, GameConfig& c);
void to_json(nlohmann::json& j, const AgentConfig& c);
void from_json(const nlohmann::json& j, AgentConfig& c);

}  // namespace peg3d::game
