#pragma once
// Configuration of a pursuit-evasion game: timing, termination, teams, and per agent its kinematics, policy,
// observation, reward and learner. Every struct lists its fields once, with unit, valid range and meaning,
// in a visit_fields() table (core/config_fields.hpp) that drives validation, JSON in and out, `--set` and
// `--list-config`. Named presets give the paper's configuration, peg3d's default and the baseline
// (docs/paper-notes.md explains each difference).

#include <concepts>
#include <string>
#include <type_traits>
#include <vector>

#include "core/config_fields.hpp"
#include "fuzzy/facl_learner.hpp"
#include "geometry/kinematics.hpp"
#include "sense/lidar.hpp"
#include "sense/scan_map.hpp"

namespace peg3d::game {

enum class Role { kPursuer, kEvader };
const char* to_string(Role r);

/// Agent i of a game's order (a scenario's, a SimState's): `pursuers` pursuers first, then the evaders. Its
/// role, and its rank k among the agents of that role.
constexpr Role role_at(int i, int pursuers) { return i < pursuers ? Role::kPursuer : Role::kEvader; }
constexpr int rank_at(int i, int pursuers) { return i < pursuers ? i : i - pursuers; }
/// The one name of agent `rank` (0 first) of a role, everywhere peg3d names agents: trajectory files, collision
/// logs and cases, replays, results, Python (its agents, its `opponents` keys): "pursuer_0", "evader_1", ... The
/// "<group>_<int>" form is the one multi-agent libraries group agents by (TorchRL, VMAS, BenchMARL).
std::string agent_label(Role role, int rank);

/// A label in the current form for one peg3d wrote before issue 37 (collision logs of format 1, collision cases,
/// trajectory files): the role alone, which named the only agent of its role ("pursuer" -> "pursuer_0"), or role
/// and rank run together ("evader1" -> "evader_1"). Any other text comes back unchanged.
std::string current_agent_label(const std::string& label);

/// Who drives an agent when the game is played by policies (an external caller may instead pass its own
/// steering commands to step()).
enum class PolicyKind {
  kFacl,                    ///< fuzzy actor-critic learning (both roles)
  kPurePursuit,             ///< head straight at the opponent (pursuer)
  kProportionalNavigation,  ///< 3D proportional navigation with gain pn_gain (pursuer)
  kApollonius,              ///< aim at the Apollonius interception point (pursuer)
  kFlee,                    ///< flee along the line of sight, repelled by walls and obstacles (evader)
  kFleeApollonius,          ///< head for the far side of the evader's dominance region (evader)
  kRandom,                  ///< random steering within the bound (both roles)
  kSearch,                  ///< the partial game: chase in sight, else go to the last sighting and search (pursuer)
  kHide,                    ///< the partial game: break line of sight behind an occluder when seen, else flee (evader)
};
inline constexpr config::EnumNames<PolicyKind, 9> kPolicyNames{{{PolicyKind::kFacl, "facl"},
                                                                {PolicyKind::kPurePursuit, "pure-pursuit"},
                                                                {PolicyKind::kProportionalNavigation, "pn"},
                                                                {PolicyKind::kApollonius, "apollonius"},
                                                                {PolicyKind::kFlee, "flee"},
                                                                {PolicyKind::kFleeApollonius, "flee-apollonius"},
                                                                {PolicyKind::kRandom, "random"},
                                                                {PolicyKind::kSearch, "search"},
                                                                {PolicyKind::kHide, "hide"}}};
const char* to_string(PolicyKind p);
/// Whether a policy can play `role` (facl and random play both; guidance laws pursue; flee policies evade).
bool plays(PolicyKind p, Role role);
/// The policy called `name` for `role`; throws InvalidParameter naming `field` for an unknown name or one
/// that does not play the role.
PolicyKind policy_named(const std::string& name, Role role, const std::string& field);

/// Which angle errors the observation carries.
enum class AngleInputs {
  kAzimuth,           ///< paper: one signed azimuth error per direction (target, obstacle)
  kAzimuthElevation,  ///< a signed azimuth and a signed elevation error per direction
};
inline constexpr config::EnumNames<AngleInputs, 2> kAngleInputNames{
    {{AngleInputs::kAzimuth, "azimuth"}, {AngleInputs::kAzimuthElevation, "azimuth-elevation"}}};

/// The line the evader's target angle is measured from.
enum class EvaderReference {
  kTowardPursuer,    ///< paper eq. (20): from E->P, so fleeing straight away reads +-pi (the wrap point)
  kAwayFromPursuer,  ///< from P->E, so fleeing straight away reads 0
};
inline constexpr config::EnumNames<EvaderReference, 2> kEvaderReferenceNames{
    {{EvaderReference::kTowardPursuer, "toward-pursuer"}, {EvaderReference::kAwayFromPursuer, "away-from-pursuer"}}};

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

enum class RewardKind {
  kPotentialField,  ///< paper eq. (15)-(18): w_r r_O + w_a r_PE + r_s
  kDistanceOnly,    ///< baseline: the normalised change of d_PE, (d(t) - d(t+1)) / ((vP + vE) dt)
};
inline constexpr config::EnumNames<RewardKind, 2> kRewardKindNames{
    {{RewardKind::kPotentialField, "potential-field"}, {RewardKind::kDistanceOnly, "distance-only"}}};

/// How the paper's "inverted" terms are read for the evader.
enum class EvaderInversion {
  kNegate,  ///< r_E = -r_P term by term: 1 - exp(-beta dd), -gamma_s g (the repulsion form)
  kMirror,  ///< the sign of the argument flips: exp(beta dd) - 1, -gamma_s g
};
inline constexpr config::EnumNames<EvaderInversion, 2> kEvaderInversionNames{
    {{EvaderInversion::kNegate, "negate"}, {EvaderInversion::kMirror, "mirror"}}};

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

/// Which opponent an agent observes, is rewarded against and (with the motion space) steers relative to.
enum class OpponentChoice {
  kNearest,   ///< the nearest opponent still in the game (ties: the lower index)
  kAssigned,  ///< opponent k mod n for the agent's index k among its role, while that one is in the game;
              ///< the nearest one after
};
inline constexpr config::EnumNames<OpponentChoice, 2> kOpponentChoiceNames{
    {{OpponentChoice::kNearest, "nearest"}, {OpponentChoice::kAssigned, "assigned"}}};

/// Which pairs of agents collide with each other (spheres of their radii, swept over each step).
enum class AgentCollisions {
  kNone,       ///< agents pass through each other (the paper)
  kOpponents,  ///< pursuers with evaders
  kTeammates,  ///< pursuers with pursuers and evaders with evaders
  kAll,        ///< every pair
};
inline constexpr config::EnumNames<AgentCollisions, 4> kAgentCollisionNames{{{AgentCollisions::kNone, "none"},
                                                                            {AgentCollisions::kOpponents, "opponents"},
                                                                            {AgentCollisions::kTeammates, "teammates"},
                                                                            {AgentCollisions::kAll, "all"}}};

/// Who receives the capture term r_s of a capture.
enum class CaptureReward {
  kIndividual,  ///< the capturing pursuer (+gamma_s) and the captured evader (-gamma_s)
  kTeam,        ///< every pursuer (+gamma_s), and the captured evader and every evader still free (-gamma_s)
};
inline constexpr config::EnumNames<CaptureReward, 2> kCaptureRewardNames{
    {{CaptureReward::kIndividual, "individual"}, {CaptureReward::kTeam, "team"}}};

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

/// Where an agent's nearest-obstacle inputs (d_O and its angles, the Python entries 3-5 and 17-19) and its
/// obstacle guard come from.
enum class ObstacleSource {
  kWorld,   ///< the world as it is: the map's distance field and the movers where they are (today's default)
  kOwnMap,  ///< the agent's own map built from its scans (AgentConfig::map): the nearest occupied cell
};
inline constexpr config::EnumNames<ObstacleSource, 2> kObstacleSourceNames{
    {{ObstacleSource::kWorld, "world"}, {ObstacleSource::kOwnMap, "own-map"}}};

struct ObservationConfig {
  AngleInputs angles = AngleInputs::kAzimuthElevation;
  EvaderReference evader_reference = EvaderReference::kAwayFromPursuer;
  bool boundary_is_obstacle = true;  ///< floor, ceiling and walls count in d_O, its direction and r_O
  /// The opponent's heading as an input: its signed azimuth (and, with azimuth-elevation, elevation) error
  /// from the opponent's heading to the line P->E. 0 when a pursuer heads straight at the evader or an evader
  /// flees straight away; an interceptor's lead shows as the pursuer's error. Adds one input per channel.
  bool opponent_heading = false;
  double target_range = 35.0;        ///< m, d_PE partition [0, target_range], > 0 (paper 35)
  double obstacle_range = 5.0;       ///< m, d_O partition [0, obstacle_range], > 0 (paper 35)
  int sets = 5;                      ///< triangular sets per input, in [2, 64] (paper 5)
  /// The nearest obstacle: the world's, or the agent's own map's (needs map.enabled). The arena's faces stay
  /// known to the agent either way (boundary_is_obstacle).
  ObstacleSource obstacles = ObstacleSource::kWorld;
  bool operator==(const ObservationConfig&) const = default;
};

/// What an agent with limited sight estimates an opponent it does not see now to be doing (SightConfig::estimate).
enum class SightEstimate {
  kLastSeen,       ///< where it was last seen, heading as it was
  kDeadReckoning,  ///< where it was last seen, moved on since at the velocity it had then (kept in the arena)
};
inline constexpr config::EnumNames<SightEstimate, 2> kSightEstimateNames{
    {{SightEstimate::kLastSeen, "last-seen"}, {SightEstimate::kDeadReckoning, "dead-reckoning"}}};

/// Opponents seen only in line of sight (issue 39, docs/sight.md). Off (the default): the agent knows every
/// opponent's state at every step, the paper's full information. On: after each step (and at the reset) the
/// agent looks at every opponent in the game; it sees one when the opponent's centre is within `range`, within
/// the field of view (the angle between the agent's heading and the line to that centre is at most fov / 2),
/// and a sight ray reaches the opponent's sphere before any terrain, obstacle or mover (sense/line_of_sight.hpp:
/// `points` rays; other agents do not hide it). Each agent remembers its latest sighting of each opponent
/// (position, heading, velocity, when); every agent starts knowing where each opponent starts. Its opponent
/// inputs (the percept, the motion space, the Python entries) come from the estimate built on that sighting;
/// its rewards still measure the true distance.
struct SightConfig {
  bool enabled = false;  ///< limited sight; false: full information (the default)
  double range = 100.0;  ///< m, in (0, 1000]: the farthest an opponent's centre can be seen
  double fov = 360.0;    ///< deg, in (0, 360]: the field of view's full angle about the heading (360: all round)
  int points = 5;        ///< sight rays per look at an opponent, in [1, 9]: its centre, then points of its rim
  SightEstimate estimate = SightEstimate::kLastSeen;  ///< what the inputs hold while the opponent is out of sight
  /// Teammates share sightings: every agent of the role with share on holds the newest sighting any of them
  /// has of each opponent, and sees what any of them sees.
  bool share = false;
  bool operator==(const SightConfig&) const = default;
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
  bool operator==(const RewardConfig&) const = default;
};

/// A safety layer on top of any policy: near an obstacle of the map (and, with `faces`, the arena boundary),
/// headings that approach it are excluded, like the motion space excludes headings that lose ground. Within
/// `stop_distance` of the obstacle the heading may not approach it at all; between `stop_distance` and
/// `warn_distance` the excluded cone about the direction to the obstacle narrows linearly to nothing. As a
/// last resort, measured on the exact shapes rather than the distance field, no step ends nearer than the
/// radius plus kHoldMargin (game/constraints.hpp) to a static obstacle: an agent with the guard on does not
/// run into one.
struct ObstacleGuard {
  bool enabled = true;
  bool faces = false;          ///< the arena's floor, ceiling and walls are guarded against too (nearest of both)
  double stop_distance = 0.8;  ///< m, > 0; covers radius + one step + the distance field's voxel error
  double warn_distance = 2.0;  ///< m, > stop_distance
  /// m, in [0, stop_distance): the guard also keeps clear of a second obstacle, the one nearest to the point
  /// this far ahead along the guarded heading, once it is nearer than stop_distance (sliding past one trunk
  /// into the next). Shorter than stop_distance so that a point inside the obstacle still counts. 0: the
  /// nearest obstacle only.
  double look_ahead = 0.6;
  bool operator==(const ObstacleGuard&) const = default;
};

/// One agent: who drives it and how it moves, senses, is rewarded and learns.
struct AgentConfig {
  PolicyKind policy = PolicyKind::kFacl;
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
  sense::LidarConfig lidar;  ///< its range sensor (none by default)
  sense::ScanMapConfig map;  ///< its own occupancy map, built from its lidar's scans (none by default)
  SightConfig sight;         ///< opponents seen only in line of sight (off by default: full information)
  bool operator==(const AgentConfig&) const = default;
};

/// How several pursuers and evaders play together (the paper's 1 v 1 is a team of one each).
struct TeamConfig {
  OpponentChoice pursuer_target = OpponentChoice::kNearest;  ///< the evader a pursuer plays against
  OpponentChoice evader_threat = OpponentChoice::kNearest;   ///< the pursuer an evader plays against
  AgentCollisions agent_collisions = AgentCollisions::kNone;
  CaptureReward capture_reward = CaptureReward::kIndividual;
  bool operator==(const TeamConfig&) const = default;

  /// The rule by which an agent of `role` chooses its opponent.
  OpponentChoice opponent_rule(Role role) const { return role == Role::kPursuer ? pursuer_target : evader_threat; }
  /// Whether an agent of role a and one of role b collide (agent_collisions).
  bool collide(Role a, Role b) const {
    switch (agent_collisions) {
      case AgentCollisions::kNone: return false;
      case AgentCollisions::kOpponents: return a != b;
      case AgentCollisions::kTeammates: return a == b;
      case AgentCollisions::kAll: return true;
    }
    return false;
  }
};

/// How the FACL agents of a trial train (the experiments carry it out: experiment/training.hpp,
/// docs/learning.md). The defaults are the paper's procedure.
enum class TrainingProcedure {
  kCoLearning,    ///< the paper: every episode, the FACL pursuers and evaders learn against each other
  kOpponentPool,  ///< a share of the episodes, one FACL role learns against a classic opponent of the pool
};
inline constexpr config::EnumNames<TrainingProcedure, 2> kTrainingProcedureNames{
    {{TrainingProcedure::kCoLearning, "co-learning"}, {TrainingProcedure::kOpponentPool, "opponent-pool"}}};

struct TrainingConfig {
  TrainingProcedure procedure = TrainingProcedure::kCoLearning;
  /// Opponent pool: the share of training episodes, in [0, 1], in which one FACL role (drawn uniformly with
  /// the opponent) plays a classic opponent instead of its co-learning partner.
  double pool_share = 0.5;
  bool pool_pure_pursuit = true;     ///< the FACL evaders' pool includes pure pursuit
  bool pool_pn = true;               ///< ... proportional navigation
  bool pool_apollonius = true;       ///< ... the Apollonius interceptor
  bool pool_flee = true;             ///< the FACL pursuers' pool includes flee
  bool pool_flee_apollonius = true;  ///< ... flee-apollonius
  bool pool_random = true;           ///< ... the random evader
  /// Share of training episodes, in [0, 1], whose agents start at random places in the arena (random_start.hpp)
  /// instead of the scenario's; the scenario still gives how many agents play.
  double random_starts = 0.0;
  double random_start_gap = 20.0;  ///< m, >= 0: least distance from a pursuer to an evader at a random start
  /// Share of the training episodes, in (0, 1], in which the pursuers learn: the first ones. Afterwards they
  /// play their policy greedily without learning, and the opponent pool leaves out their entries.
  double pursuer_learning = 1.0;
  double evader_learning = 1.0;  ///< likewise for the evaders
  bool operator==(const TrainingConfig&) const = default;
};

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
  TrainingConfig training;

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

/// The configuration a scripted policy plays with: the base agent's kinematics and guard, its own policy,
/// no motion space and no learning.
AgentConfig scripted_agent(const AgentConfig& base, PolicyKind policy);
/// `config` with every agent of `role` (its default and each per-agent entry) playing the scripted `policy`.
GameConfig with_role_playing(GameConfig config, Role role, PolicyKind policy);

/// The preset names: "peg3d" (the default), "paper" (as faithful as the text allows), "baseline" (FACL in
/// the manner of Al-Mahbashi et al. 2020 for the pursuer) and "robust" (peg3d trained with an opponent pool,
/// docs/learning.md).
inline constexpr const char* kPresetNames[] = {"peg3d", "paper", "baseline", "robust"};
/// kPresetNames as text for messages and help: "peg3d, paper, baseline, robust".
std::string preset_list();
/// A named configuration. Throws InvalidParameter for an unknown name.
GameConfig preset(const std::string& name);
/// The preset's settings for one agent (the pursuer's or the evader's side of that preset).
AgentConfig agent_preset(const std::string& name, Role role);

/// The most rules one FACL channel may have (2^20: 24 MB of tables); bounds what a config or policy can allocate.
inline constexpr long long kMaxFaclRules = 1LL << 20;
/// Rules of each FACL channel: sets^inputs, inputs 4 (azimuth, or one channel per angle) or 6 (joint
/// azimuth-elevation), plus one per observed angle of the opponent's heading.
constexpr long long facl_rules(const AgentConfig& c) {
  const bool joint_both =
      c.structure == FaclStructure::kJoint && c.observation.angles == AngleInputs::kAzimuthElevation;
  const int inputs = (joint_both ? 6 : 4) + (c.observation.opponent_heading ? (joint_both ? 2 : 1) : 0);
  long long rules = 1;
  for (int i = 0; i < inputs; ++i) rules *= c.observation.sets;
  return rules;
}

// ---- Field tables (core/config_fields.hpp) ----

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, ObservationConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.choice("angles", c.angles, kAngleInputNames,
           "angle errors observed: the azimuth only (the paper) or azimuth and elevation");
  v.choice("evader_reference", c.evader_reference, kEvaderReferenceNames,
           "line the evader's target angle is measured from (paper: toward-pursuer)");
  v.flag("boundary_is_obstacle", c.boundary_is_obstacle,
         "the arena's floor, ceiling and walls count as the nearest obstacle in d_O and r_O");
  v.flag("opponent_heading", c.opponent_heading,
         "the opponent's heading, as its angle errors to the line P->E, is one more input of each FACL channel");
  v.number("target_range", c.target_range, Range::positive(), "m", "d_PE is partitioned over [0, target_range] (paper 35)");
  v.number("obstacle_range", c.obstacle_range, Range::positive(), "m",
           "d_O is partitioned over [0, obstacle_range] (paper 35)");
  v.integer("sets", c.sets, 2, 64, "", "triangular fuzzy sets per input (paper 5)");
  v.choice("obstacles", c.obstacles, kObstacleSourceNames,
           "the nearest obstacle of the inputs and the guard: the world's, or the agent's own map's (needs map.enabled)");
}

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, SightConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.flag("enabled", c.enabled, "opponents are seen only in line of sight (false: full information, the default)");
  v.number("range", c.range, Range::open_closed(0, 1000), "m", "the farthest an opponent's centre can be seen");
  v.number("fov", c.fov, Range::open_closed(0, 360), "deg",
           "the field of view's full angle about the heading, a cone (360: all round)");
  v.integer("points", c.points, 1, 9, "", "sight rays per look at an opponent: its centre, then points of its rim");
  v.choice("estimate", c.estimate, kSightEstimateNames,
           "an opponent out of sight is where it was last seen, or moved on at its velocity then (dead-reckoning)");
  v.flag("share", c.share, "teammates with share on pool their sightings");
}

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, RewardConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.choice("kind", c.kind, kRewardKindNames, "the paper's potential-field reward or the baseline's distance change");
  v.number("alpha_r", c.alpha_r, Range::non_negative(), "1/m", "repulsion coefficient of r_O, eq. 15 (paper 10)");
  v.number("beta_a", c.beta_a, Range::non_negative(), "1/m", "attraction coefficient of r_PE, eq. 16 (paper 5)");
  v.number("gamma_s", c.gamma_s, Range::non_negative(), "", "capture reward r_s, eq. 17 (paper 20)");
  v.number("w_r", c.w_r, Range::non_negative(), "", "weight of r_O, eq. 18 (paper 5)");
  v.number("w_a", c.w_a, Range::non_negative(), "", "weight of r_PE, eq. 18 (paper 10)");
  v.choice("inversion", c.inversion, kEvaderInversionNames, "how the evader's terms invert the pursuer's");
  v.number("collision_penalty", c.collision_penalty, Range::non_negative(), "",
           "subtracted from the reward of an agent that hits an obstacle (paper: none)");
}

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, ObstacleGuard>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.flag("enabled", c.enabled, "exclude headings that approach a nearby obstacle of the map");
  v.flag("faces", c.faces, "the arena's floor, ceiling and walls count as obstacles of the guard (the nearer one is guarded)");
  v.number("stop_distance", c.stop_distance, Range::positive(), "m", "closer than this, no heading may approach it");
  v.number("warn_distance", c.warn_distance, Range::positive(), "m",
           "from here to stop_distance the excluded cone widens to a half-space");
  v.require(c.warn_distance > c.stop_distance, "warn_distance", c.warn_distance, "must be > guard.stop_distance");
  v.number("look_ahead", c.look_ahead, Range::non_negative(), "m",
           "also keep clear of the obstacle nearest to the point this far ahead once within stop_distance (0: off)");
  v.require(c.look_ahead < c.stop_distance, "look_ahead", c.look_ahead, "must be < guard.stop_distance");
}

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, AgentConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.choice("policy", c.policy, kPolicyNames, "who drives the agent");
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
  v.section("lidar", c.lidar, "the agent's range sensor (sense/lidar.hpp); none by default");
  v.section("map", c.map, "the agent's occupancy map from its own scans (sense/scan_map.hpp); none by default");
  v.section("sight", c.sight, "opponents seen only in line of sight (docs/sight.md); off by default");
  v.require(!c.map.enabled || c.lidar.enabled(), "map.enabled", "true", "needs a lidar (lidar.azimuth_rays > 0)");
  v.require(c.observation.obstacles != ObstacleSource::kOwnMap || c.map.enabled, "observation.obstacles", "own-map",
            "needs map.enabled");
  v.require(c.structure != FaclStructure::kPerAngle || c.observation.angles == AngleInputs::kAzimuthElevation,
            "structure", "per-angle", "needs observation.angles = azimuth-elevation");
  // sets^inputs rules, each a row of the actor and critic: without a bound, 64 sets over 6 inputs asks for 10^11.
  v.require(facl_rules(c) <= kMaxFaclRules, "observation.sets", c.observation.sets,
            "gives more than 2^20 FACL rules per channel (sets^inputs: 4 inputs, or 6 with azimuth-elevation joint)");
}

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, TeamConfig>
void visit_fields(V& v, C& c) {
  v.choice("pursuer_target", c.pursuer_target, kOpponentChoiceNames, "the evader each pursuer plays against");
  v.choice("evader_threat", c.evader_threat, kOpponentChoiceNames, "the pursuer each evader plays against");
  v.choice("agent_collisions", c.agent_collisions, kAgentCollisionNames, "which pairs of agents collide");
  v.choice("capture_reward", c.capture_reward, kCaptureRewardNames, "who receives the capture term r_s");
}

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, TrainingConfig>
void visit_fields(V& v, C& c) {
  using config::Range;
  v.choice("procedure", c.procedure, kTrainingProcedureNames,
           "co-learning (the paper) or opponent-pool (co-learning mixed with episodes against classic opponents)");
  v.number("pool_share", c.pool_share, Range::closed(0, 1), "",
           "opponent-pool: share of training episodes in which one FACL role plays a classic opponent");
  v.flag("pool_pure_pursuit", c.pool_pure_pursuit, "opponent-pool: FACL evaders train against pure pursuit");
  v.flag("pool_pn", c.pool_pn, "opponent-pool: FACL evaders train against proportional navigation");
  v.flag("pool_apollonius", c.pool_apollonius, "opponent-pool: FACL evaders train against the Apollonius interceptor");
  v.flag("pool_flee", c.pool_flee, "opponent-pool: FACL pursuers train against flee");
  v.flag("pool_flee_apollonius", c.pool_flee_apollonius, "opponent-pool: FACL pursuers train against flee-apollonius");
  v.flag("pool_random", c.pool_random, "opponent-pool: FACL pursuers train against the random evader");
  v.number("random_starts", c.random_starts, Range::closed(0, 1), "",
           "share of training episodes that start at random places in the arena instead of the scenario's");
  v.number("random_start_gap", c.random_start_gap, Range::non_negative(), "m",
           "least distance from a pursuer to an evader at a random start");
  v.number("pursuer_learning", c.pursuer_learning, Range::open_closed(0, 1), "",
           "share of the training episodes (the first ones) in which the pursuers learn");
  v.number("evader_learning", c.evader_learning, Range::open_closed(0, 1), "",
           "share of the training episodes (the first ones) in which the evaders learn");
  v.require(c.procedure != TrainingProcedure::kOpponentPool || c.pool_pure_pursuit || c.pool_pn || c.pool_apollonius ||
                c.pool_flee || c.pool_flee_apollonius || c.pool_random,
            "procedure", "opponent-pool", "needs at least one pool_* opponent");
}

namespace detail {
/// The role rules of one agent's settings (its policy plays the role; a pursuer moves).
template <class V>
void require_role(V& v, const AgentConfig& a, Role role, const std::string& prefix) {
  v.require(plays(a.policy, role), prefix + ".policy", to_string(a.policy),
            role == Role::kPursuer ? "is not a pursuer policy (facl, pure-pursuit, pn, apollonius, random, search)"
                                   : "is not an evader policy (facl, flee, flee-apollonius, random, hide)");
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
  v.section("training", c.training, "how FACL agents train (docs/learning.md)");
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
