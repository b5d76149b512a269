#pragma once
// One agent's settings: who drives it, how it moves, senses, is rewarded and learns. Each part is declared beside
// the code it configures (steering: geometry/kinematics.hpp, the guard: game/obstacle_guard.hpp, the percept:
// game/percept.hpp, the reward: game/reward.hpp, FACL's rates: fuzzy/facl_learner.hpp, the sensors and the own
// map: sense/); this header composes them, with the few fields that belong to the agent itself.

#include <concepts>
#include <string>
#include <type_traits>

#include "core/config_fields.hpp"
#include "fuzzy/facl_learner.hpp"
#include "game/obstacle_guard.hpp"
#include "game/percept.hpp"
#include "game/reward.hpp"
#include "game/role.hpp"
#include "geometry/kinematics.hpp"
#include "sense/scan_map.hpp"
#include "sense/sensors.hpp"

namespace peg3d::game {

/// How FACL turns observations into the two steering angles.
enum class FaclStructure {
  kJoint,     ///< one actor-critic over all inputs with two outputs (the paper)
  kPerAngle,  ///< one actor-critic per steering angle, each over d_PE, its target error, d_O and its obstacle error
};
inline constexpr config::EnumNames<FaclStructure, 2> kFaclStructureNames{
    {{FaclStructure::kJoint, "joint"}, {FaclStructure::kPerAngle, "per-angle"}}};

/// What a FACL actor's outputs are. A residual: with kTargetLineOffset a fresh actor (outputs 0) already flies
/// pure pursuit (a pursuer) or straight away from its pursuer (an evader, away-from-pursuer reference), and
/// learning shapes corrections to that instead of the whole turn.
enum class FaclAction {
  kHeadingChange,     ///< the paper: the outputs are the changes of azimuth and polar angle
  kTargetLineOffset,  ///< the outputs are added to the turn onto the line the target angles are measured from
};
inline constexpr config::EnumNames<FaclAction, 2> kFaclActionNames{
    {{FaclAction::kHeadingChange, "heading-change"}, {FaclAction::kTargetLineOffset, "target-line-offset"}}};

/// One agent: who drives it and how it moves, senses, is rewarded and learns.
struct AgentConfig {
  /// Who drives it when the game is played by policies: a player's name (players/registry.hpp, `--list-players`),
  /// checked against the registry where players are made. An external caller may instead pass its own steering
  /// commands to step().
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
  FaclAction action = FaclAction::kHeadingChange;
  double pn_gain = 3.0;  ///< proportional-navigation constant N, > 0
  /// Its sensors' settings (sense/sensors.hpp), each a section of its own beside the others ("sight", "lidar", ...):
  /// none by default, the paper's full information.
  sense::SensorSettings sensors;
  sense::ScanMapConfig map;  ///< its own occupancy map, built from its sensors' scans (none by default)
  bool operator==(const AgentConfig&) const = default;
};

/// The most rules one FACL channel may have (2^20: 24 MB of tables); bounds what a config or policy can allocate.
inline constexpr long long kMaxFaclRules = 1LL << 20;
/// Inputs of each FACL channel: 4 (azimuth, or one channel per angle) or 6 (joint azimuth-elevation), plus one per
/// observed angle of the opponent's heading, plus two with the sight inputs.
constexpr int facl_inputs(const AgentConfig& c) {
  const bool joint_both =
      c.structure == FaclStructure::kJoint && c.observation.angles == AngleInputs::kAzimuthElevation;
  return (joint_both ? 6 : 4) + (c.observation.opponent_heading ? (joint_both ? 2 : 1) : 0) +
         (c.observation.sight_inputs ? 2 : 0);
}
/// The most inputs a FACL channel takes (fuzzy::kMaxInputs: 2^8 rules fire at once).
inline constexpr int kMaxFaclInputs = 8;
/// Rules of each FACL channel: the product of its inputs' set counts, `sets` each but the sight's visibility (2).
constexpr long long facl_rules(const AgentConfig& c) {
  const int inputs = facl_inputs(c);
  long long rules = c.observation.sight_inputs ? 2 : 1;
  for (int i = c.observation.sight_inputs ? 1 : 0; i < inputs; ++i) rules *= c.observation.sets;
  return rules;
}

// ---- Field table (core/config_fields.hpp) ----

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, AgentConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.name("policy", c.policy, "a player (--list-players)", "who drives the agent");
  v.number("speed", c.speed, Range::non_negative(), "m/s",
           "constant speed; a pursuer's > 0, an evader may stand still (paper 1.1 and 1.0)");
  v.number("radius", c.radius, Range::positive(), "m", "collision sphere (the paper gives none)");
  v.section("steering", c.steering, "steering bound and climb limit");
  v.flag("motion_space", c.motion_space, "keep the heading in the paper's optimal motion space (section 3.1)");
  v.section("guard", c.guard, "the obstacle guard");
  v.section("observation", c.observation, "FACL inputs");
  v.section("reward", c.reward, "reward terms");
  v.section("facl", c.facl, "FACL learning rates and exploration");
  v.choice("structure", c.structure, kFaclStructureNames, "one joint learner (the paper) or one per steering angle");
  v.choice("action", c.action, kFaclActionNames,
           "the actor's outputs: the heading change (the paper) or an offset to the turn onto the target line");
  v.number("pn_gain", c.pn_gain, Range::positive(), "", "proportional-navigation constant N");
  v.embed(c.sensors);
  v.section("map", c.map, "the agent's occupancy map from its own scans (sense/scan_map.hpp); none by default");
  v.require(!c.map.enabled || sense::feeds_map(c.sensors), "map.enabled", "true", sense::kMapFeeders);
  v.require(c.observation.obstacles != ObstacleSource::kOwnMap || c.map.enabled, "observation.obstacles", "own-map",
            "needs map.enabled");
  v.require(c.structure != FaclStructure::kPerAngle || c.observation.angles == AngleInputs::kAzimuthElevation,
            "structure", "per-angle", "needs observation.angles = azimuth-elevation");
  // sets^inputs rules, each a row of the actor and critic: without a bound, 64 sets over 6 inputs asks for 10^11.
  v.require(facl_inputs(c) <= kMaxFaclInputs, "observation.sight_inputs", "true",
            "gives more than 8 FACL inputs per channel (joint azimuth-elevation with opponent_heading takes 8 already)");
  v.require(facl_rules(c) <= kMaxFaclRules, "observation.sets", c.observation.sets,
            "gives more than 2^20 FACL rules per channel (sets^inputs: 4 inputs, or 6 with azimuth-elevation joint)");
}

}  // namespace peg3d::game
