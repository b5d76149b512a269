#pragma once
// The steppable game, in the manner of MuJoCo's mj_step(const mjModel*, mjData*):
//   Sim        the read-only model: the Arena, the GameConfig and what derives from them. Shared by all
//              threads.
//   SimState   one run's changing state: every agent's kinematic state, time and step, which evaders are
//              still free, the run's totals, its random engine and its collision scratch (a Bullet world).
//   reset      puts a state at a scenario's start; step turns it into the next state given one steering
//              command per agent and reports what happened (StepEvents).
// Every loop (play(), experiments, replays of recorded motions, external controllers) is built on step().
//
// Agents are indexed pursuers first, then evaders, each in the scenario's order. Each step:
//   every active agent's command -> bounded steering -> motion space -> obstacle guard   (constraints.hpp)
//   -> move along the heading, clamped to the arena -> swept collision with the map's obstacles
//   -> (optionally) swept collision between agents -> captures -> sensors' readings due -> new observations -> rewards.

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/random.hpp"
#include "game/constraints.hpp"
#include "game/game_config.hpp"
#include "game/percept.hpp"
#include "game/policy.hpp"
#include "game/reward.hpp"
#include "game/starts.hpp"
#include "sense/scan_map.hpp"
#include "sense/sensor.hpp"
#include "sense/world_rays.hpp"
#include "world/arena.hpp"
#include "world/collision/collision_world.hpp"
#include "world/bodies/mover_timeline.hpp"
#include "world/moving_field.hpp"
#include "world/bodies/push_world.hpp"

namespace peg3d::game {

/// An agent touching an obstacle or another agent: the query's contact record (agent, what it hit, where),
/// with when and the agent's role.
struct CollisionEvent : world::Contact {
  int step = 0;                ///< the step during which it happened (1 = the first step)
  double time = 0.0;           ///< s, time of impact within the episode
  Role role = Role::kPursuer;  ///< the agent's role
};

/// An agent touching a pushable dynamic body (push mode), the push world's contact record (kind kMover,
/// obstacle_id the body's index in the map's movers, `pushed`) with when: logged, not a collision.
struct PushEvent : world::Contact {
  int step = 0;       ///< the step during which it happened (1 = the first step)
  double time = 0.0;  ///< s, the end of the physics substep it was found at
};

/// A pursuer coming within the capture distance of a free evader at the end of a step.
struct CaptureEvent {
  int step = 0;
  double time = 0.0;      ///< s
  int pursuer = 0;        ///< index of the capturing pursuer (the nearest; the lower index on a tie)
  int evader = 0;         ///< index of the captured evader
  double distance = 0.0;  ///< m, their distance at the capture
};

/// One agent's state in a run, and its running totals.
struct AgentState {
  Role role = Role::kPursuer;
  int rank = 0;                       ///< index among the agents of its role
  /// its settings (owned by the Sim): its own, or as a classic player plays them (Sim::scripted_config)
  const AgentConfig* config = nullptr;
  KinematicState kinematics;
  Box bounds;                         ///< the arena shrunk by its radius: where its centre may go
  bool active = true;                 ///< in the game; an evader leaves it when captured
  int opponent = -1;                  ///< index of the agent it plays against now
  /// What it may use to decide now: its percept relative to `opponent`, the map's nearest obstacle (arena
  /// faces excluded), both agents' states. Rebuilt by reset() and by every step() it takes part in.
  AgentView view;
  int body = -1;                      ///< its sphere in the state's collision world
  /// The view's word on the movers: at `at`, time `time` (s), every mover queried by the timeline lay at least
  /// `distance` (m) away (the field's distance: a mover's, or the cap no mover came within). The step's mover
  /// contacts need no query when the agent starts there and then and no mover can close that gap
  /// (MoverTimeline::clear_of_contact). `time` < 0: no such word (no exact mover sensing).
  struct {
    Vec3 at = Vec3::Zero();
    double time = -1.0;
    double distance = 0.0;
  } mover_clearance;
  int nearest_mover = -1;             ///< the timeline's nearest mover at the last view (-1: none), its next hint
  // Totals over the run so far.
  double path = 0.0;                  ///< m travelled
  double total_reward = 0.0;          ///< undiscounted sum of its rewards
  int steps = 0;                      ///< steps it took part in
  int pinned_steps = 0;               ///< steps ending with its centre within max(radius, 0.1 m) of a face
  int collisions = 0;                 ///< collision events it caused
  int captures = 0;                   ///< evaders it captured (pursuers)
  double captured_at = -1.0;          ///< s, when it was captured (evaders; < 0 while free)
};

/// What happened to one agent in a step.
struct AgentEvents {
  Steering command;             ///< the command it was given
  RewardTerms reward;           ///< its reward for the step (zero for an agent that was out of the game)
  int opponent = -1;            ///< the opponent its reward terms were measured against
  bool collided = false;        ///< it hit an obstacle or an agent (the first contact is in StepEvents::collisions)
  int captures = 0;             ///< evaders it captured in this step (pursuer)
  bool captured = false;        ///< it was captured in this step (evader)
  bool terminal = false;        ///< the step ended the game for it (its capture, the last capture, a terminating collision)
  bool acted = false;           ///< it was in the game at the start of the step
};

/// How an episode ended.
enum class Outcome {
  kCapture,           ///< every evader captured
  kTimeout,           ///< time_limit reached
  kPursuerCollision,  ///< a pursuer hit something (CollisionMode::kTerminate)
  kEvaderCollision,   ///< an evader hit something (CollisionMode::kTerminate)
};
const char* to_string(Outcome o);

/// What one step did. Lives in the SimState and is overwritten by the next step.
struct StepEvents {
  std::vector<AgentEvents> agents;         ///< one per agent
  std::vector<CollisionEvent> collisions;  ///< in the order detected (agents in index order); up to 3 per agent
  std::vector<CaptureEvent> captures;      ///< in evader index order
  std::vector<PushEvent> pushes;           ///< push mode: each agent's pushes, agents in index order
  /// Mover contact searches that reached their bound (world::MoverTimeline::kMaxAdvancementSteps) and answered
  /// a contact where the agent was last proved apart (world::Contact::gave_up): a collision that may not
  /// be one, never one missed. 0 in practice; peg-throughput reports the total.
  int contact_give_ups = 0;
  bool terminal = false;   ///< the game ended: every evader captured or a terminating collision
  bool truncated = false;  ///< the time limit ended it (not a terminal state of the game: learners bootstrap)
};

class Sim;

/// One run's changing state. Build one per thread or run; reset() reuses its storage, so resets and steps
/// of scenarios no larger than before allocate nothing. Use it only with the Sim it was made for (or a copy
/// of that Sim): its agents point at that Sim's configuration.
class SimState {
 public:
  explicit SimState(const Sim& sim);

  std::vector<AgentState> agents;  ///< pursuers first, then evaders
  int pursuers = 0;                ///< agents [0, pursuers) are pursuers, the rest evaders
  double time = 0.0;               ///< s
  int step = 0;
  int free_evaders = 0;
  bool done = false;               ///< the episode is over (terminal or truncated)
  Outcome outcome = Outcome::kTimeout;  ///< valid once done
  std::optional<CollisionEvent> first_collision;
  int collisions = 0;              ///< collision events so far
  int contact_give_ups = 0;        ///< StepEvents::contact_give_ups so far
  Rng rng;                         ///< the run's engine (random initial headings)
  world::CollisionWorld collider;  ///< per-run collision scratch over the Sim's arena (agent i is body i)
  /// With mover_sensing = octree on a map with movers: the octree and EDT that follow the movers (rebuilt by
  /// every reset, so a run does not depend on the runs before it).
  std::unique_ptr<world::MovingOccupancyField> moving_field;
  /// In push mode (Sim::pushes()): the run's own world of the dynamic bodies, with the agents (rebuilt by every
  /// reset).
  std::unique_ptr<world::PushWorld> push;
  StepEvents events;               ///< what the last step did

  /// Each agent's sensors in this run (AgentConfig::sensors, sense/sensor.hpp): their latest readings, random
  /// streams, scratch, and each agent's own map. reset() reads with every sensor; a step reads with those whose
  /// period has come (the step number a multiple of it), agents that took part in it, after the move
  /// (game/sensing.hpp). Empty when no agent carries a sensor.
  struct Sensing {
    /// One sensor an agent carries, in the order of its configuration (sense::make_sensors).
    struct Slot {
      const sense::Sensor* sensor = nullptr;
      int begin = 0;  ///< its values are [begin, begin + size) of `values` and `echo`
      int size = 0;
      Rng rng;        ///< its stream, derive_seed(the reset's seed, {sensor->stream(), agent}) when it draws
      sense::SensorScratch* scratch = nullptr;  ///< one of `scratch` below, its sensor's
    };
    /// Every scratch a sensor of this state has made (never freed, so that a later scenario that carries the same
    /// sensors in other slots makes none): the sensor, the reset that last used it, and the scratch.
    struct Scratch {
      const sense::Sensor* sensor = nullptr;
      std::uint64_t used = 0;
      std::unique_ptr<sense::SensorScratch> scratch;
    };
    std::vector<Scratch> scratch;
    std::uint64_t resets = 0;                 ///< resets so far (the scratch pool's stamp)
    std::vector<int> first;                   ///< agent i carries slots [first[i], first[i + 1])
    std::vector<Slot> slots;                  ///< never shrunk
    std::vector<sense::Reading> readings;     ///< per slot: its latest reading (spans into values and echo)
    std::vector<double> values;               ///< every slot's latest values
    std::vector<std::uint8_t> echo;           ///< ... and echoes
    /// Agent i's own map, built from its sensors' scans (AgentConfig::map; null: none). Made by the first reset that
    /// needs it, cleared by every reset: a map lives for one episode, or with map.persist for as long as this
    /// state plays (a run), until forget_maps(). A map belongs to the agent's index in the scenario.
    std::vector<std::unique_ptr<sense::ScanMap>> maps;
    std::vector<int> map_step;                ///< the step agent i's map last took a scan in (-1: none)
    std::vector<const sense::Detection*> detection;  ///< agent i's detector's rules (null: full information)
    std::vector<Vec3> points;                 ///< scratch: one scan's points for a map
    std::vector<sense::Ball> balls;           ///< scratch: the agents' spheres (radius 0 out of the game)
    std::vector<std::uint8_t> targets;        ///< scratch: per agent, 1 for an opponent in the game
  } sensing;
  /// Agent i's sensors' latest readings, in the order it carries them (empty without sensors).
  std::span<const sense::Reading> readings(int i) const;
  /// Agent i's latest reading of its sensor called `name` ("lidar"); null when it carries none such.
  const sense::Reading* reading(int i, std::string_view name) const;
  /// Clears every agent's map (map.persist: a new run on this state, e.g. the next pairing of a match-up).
  void forget_maps() {
    for (auto& m : sensing.maps) {
      if (m) m->clear();
    }
  }
  /// Agent i's own map (null: none).
  const sense::ScanMap* map(int i) const {
    return std::size_t(i) < sensing.maps.size() && agents[std::size_t(i)].config->map.enabled ? sensing.maps[std::size_t(i)].get()
                                                                                              : nullptr;
  }

  /// What each agent knows of each opponent when a detector limits it (the sight sensor; game/knowledge.hpp). Entries
  /// [i * n + j] for n agents; those of pairs of one role are unused. Empty when no agent carries a detector.
  struct Sight {
    /// An agent's latest sighting of an opponent: its state then and when.
    struct Sighting {
      KinematicState state;              ///< where it was and its heading
      Vec3 velocity = Vec3::Zero();      ///< m/s, its velocity then
      double time = 0.0;                 ///< s, when (0 at the reset: every agent starts knowing the starts)
    };
    std::vector<Sighting> memory;        ///< agent i's latest sighting of agent j (its own or a teammate's)
    std::vector<std::uint8_t> visible;   ///< 1: i sees j now (itself, or a teammate it shares with)
    std::vector<std::unique_ptr<SightProbe>> probes;  ///< agent i's probe of the world now (game/knowledge.hpp)
  } sight;
  /// Whether agent i's knowledge of its opponents is limited to what its detector sees (its opponent inputs come
  /// from sight.memory).
  bool sight_limited(int i) const {
    return !sight.memory.empty() && std::size_t(i) < sensing.detection.size() && sensing.detection[std::size_t(i)] != nullptr;
  }
  /// What agent i takes agent j (an opponent) to be doing now: the truth with full information, else the estimate
  /// its sighting gives (sense::Detection::estimate).
  KinematicState known_state(int i, int j) const;
  /// How old (s) agent i's knowledge of opponent j is: 0 with full information or while it sees j.
  double sighting_age(int i, int j) const {
    return sight_limited(i) ? time - sight.memory[std::size_t(i * agent_count() + j)].time : 0.0;
  }
  /// Whether agent i sees opponent j now (always with full information).
  bool sees(int i, int j) const { return !sight_limited(i) || sight.visible[std::size_t(i * agent_count() + j)] != 0; }

  /// Every agent's kinematics at its last view, in index order: the views' `team` spans read it.
  std::vector<KinematicState> team_states;

  /// What every agent's view writes its observation with (game/observation.hpp), made by the first reset.
  std::unique_ptr<ObservationWriter> observation_writer;

  /// Per-step working storage, sized by reset().
  struct Scratch {
    std::vector<Heading> heading;         ///< each agent's heading this step, from the constraint layer
    std::vector<Vec3> direction;          ///< its unit direction
    std::vector<KinematicState> next;     ///< where each agent moves this step
    std::vector<std::optional<world::Contact>> hit;  ///< its first contact with a static obstacle this step
    std::vector<double> target_before;    ///< d to its opponent at the start of the step
    std::vector<double> obstacle_before;  ///< d_O at the start of the step
    std::vector<Vec3> position_before;    ///< m, where the agent started the step
    std::vector<Vec3> positions;          ///< start positions (reset)
    std::vector<Steering> commands;       ///< play()'s command buffer
    std::vector<Vec3> from, to;           ///< push mode: each agent's move of the step
    std::vector<world::Contact> touches;  ///< push mode: what the agents touched in the step
    std::array<world::NearPoint, kMaxHeldPoints> near;  ///< the static obstacles within an agent's hold_range
    double capture_reach2 = 0.0;          ///< squared distance beyond which no capture is possible
  } scratch;

  int agent_count() const { return static_cast<int>(agents.size()); }
  /// The agents of a role: indices [first, end) of `agents` (pursuers first, then evaders).
  struct Agents {
    int first = 0, end = 0;
  };
  Agents of_role(Role role) const { return role == Role::kPursuer ? Agents{0, pursuers} : Agents{pursuers, agent_count()}; }
  int evaders() const { return agent_count() - pursuers; }
};

/// The read-only model of a game: an arena and a configuration. Thread-safe to share.
class Sim {
 public:
  /// Validates the configuration (InvalidParameter) and checks every scenario of the arena's map against it
  /// once, before any run (StartError), so that no run can fail on its start. On a map with moving obstacles it
  /// also gets the timeline of their motion for the whole episode from the arena (one per map, shared by every
  /// Sim of it; its blocks are simulated as runs first reach them, so building a Sim simulates nothing:
  /// world/bodies/mover_timeline.hpp) and checks that the game step is a whole number of physics substeps
  /// (MapError naming physics.rate_hz).
  Sim(std::shared_ptr<const world::Arena> arena, GameConfig config);

  const GameConfig& config() const { return *config_; }
  /// Agent `rank` of `role`'s configuration as a classic player plays it: without the motion space
  /// (scripted_agent), everything else its own (game/episode.hpp, begin_playing).
  const AgentConfig& scripted_config(Role role, int rank) const { return scripted_->agent(role, rank); }
  const world::Arena& arena() const { return *arena_; }
  const std::shared_ptr<const world::Arena>& arena_ptr() const { return arena_; }
  int max_steps() const { return max_steps_; }
  /// Where the map's moving obstacles are over the whole episode (null when the map has none).
  const world::MoverTimeline* movers() const { return movers_.get(); }
  /// Whether runs simulate the map's dynamic bodies themselves, with the agents pushing (push mode on a map
  /// with dynamic bodies; then movers() holds the scripted movers alone).
  bool pushes() const { return pushes_; }
  /// Physics substeps per game step (maps with movers).
  int substeps() const { return substeps_; }
  /// Whether some agent carries a sensor (AgentConfig::sensors).
  bool senses() const { return sensing_ != nullptr; }
  /// Whether some agent's knowledge of its opponents is limited to what a detector of its sees (limited sight).
  bool limits_sight() const { return sight_; }
  /// What sensors' rays meet among the map's static solids (null when no agent carries a sensor).
  const sense::StaticRayScene* ray_scene() const { return sensing_ ? &sensing_->scene : nullptr; }
  /// The sensors agent `rank` of `role` carries, in order (empty: none).
  std::span<const sense::Sensor* const> sensors(Role role, int rank) const;
  /// Its sensor called `name` ("lidar"); null when it carries none such.
  const sense::Sensor* sensor(Role role, int rank, std::string_view name) const;

  /// Throws StartError when an agent of `scenario`, with its configured radius and kept inside the arena,
  /// starts overlapping an obstacle or (when agents collide) another agent; InvalidParameter when the
  /// scenario has no pursuer or no evader or more than kMaxAgentsPerRole of either.
  void check_scenario(const world::Scenario& scenario) const;

 private:
  std::shared_ptr<const world::Arena> arena_;
  std::shared_ptr<const GameConfig> config_;  // shared by copies: agents' config pointers stay valid
  std::shared_ptr<const GameConfig> scripted_;  // config_ with no agent's motion space (config_ when none has one)
  int max_steps_ = 0;
  std::shared_ptr<const world::MoverTimeline> movers_;
  bool pushes_ = false;
  bool sight_ = false;
  int substeps_ = 1;
  struct Sensing {
    explicit Sensing(const world::Arena& arena) : scene(arena) {}
    sense::StaticRayScene scene;
    // The sensors of each agent configuration that carries some (its sensors owned, their pointers in order).
    struct Carried {
      const AgentConfig* config = nullptr;
      std::vector<std::unique_ptr<const sense::Sensor>> owned;
      std::vector<const sense::Sensor*> sensors;
    };
    std::vector<Carried> carried;
  };
  std::shared_ptr<const Sensing> sensing_;
};

/// Puts `state` at the start of `scenario`: positions kept radius inside the arena, headings from the scenario
/// or the configured InitialHeading (kRandom draws from `seed`), first observations, totals zeroed. Throws
/// StartError like Sim::check_scenario.
void reset(const Sim& sim, SimState& state, const world::Scenario& scenario, std::uint64_t seed);

/// A step's commands that step() refuses: their count is not the state's agent count, or an agent in the game
/// was given a command that is not finite (NaN or infinity: a caller's bug, or a policy whose network
/// overflowed). what() names the step, the agent (index, role and rank) and the command, e.g.
/// "step 18: agent 0 (pursuer 0): steering command (nan, 0) rad is not finite; nothing was stepped". An
/// InputError: the commands come from the caller or from a policy file, and the programs exit 2 on it.
class CommandError : public InputError {
 public:
  /// `who` names the agent ("agent 0 (pursuer 0)"; empty for a wrong count), `detail` the problem.
  CommandError(int step, int agent, std::string who, std::string detail);
  int step() const noexcept { return step_; }    ///< the step it would have been (1 = the first)
  int agent() const noexcept { return agent_; }  ///< the agent's index; -1 for a wrong count
  int game() const noexcept { return game_; }    ///< the game of a batch (env::Batch); -1 outside one
  /// The same error, naming the policy file that played the agent: "FILE: step 18: agent 0 (pursuer 0),
  /// played by this policy file: ...".
  CommandError played_by(const std::filesystem::path& file) const;
  /// The same error, naming the game of a batch it happened in: "game 3: step 18: ...".
  CommandError in_game(int game) const;

 private:
  CommandError(int step, int agent, int game, std::string who, std::string detail, std::filesystem::path file);
  int step_ = 0, agent_ = -1, game_ = -1;
  std::string who_, detail_;
};

/// Throws CommandError unless agent i of `state` can be given `command`: finite, or the agent is out of the
/// game (then the command is ignored).
void check_command(const SimState& state, int i, const Steering& command);
/// Throws CommandError for `count` commands given to `state`, whose agent count is another.
[[noreturn]] void check_command_count(const SimState& state, std::size_t count);
/// Throws CommandError unless `commands` could be stepped from `state`: one per agent, each passing
/// check_command. step() calls it first, in every build: inline, so that finite commands cost a compare each.
inline void check_commands(const SimState& state, std::span<const Steering> commands) {
  if (commands.size() != state.agents.size()) check_command_count(state, commands.size());
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const Steering& u = commands[i];
    if (!(std::isfinite(u.d_alpha) && std::isfinite(u.d_theta))) check_command(state, static_cast<int>(i), u);
  }
}

/// Advances `state` by one sample of dt. `commands` has one steering command per agent (entries of agents
/// out of the game are ignored); the command is a requested heading change that the constraint layer
/// bounds. Returns the state's StepEvents. Throws CommandError (check_commands), leaving the state as it
/// was, when the commands cannot be stepped. The state must not be done. Allocates nothing.
const StepEvents& step(const Sim& sim, SimState& state, std::span<const Steering> commands);

/// What rays meet in `state`'s world now (sense/world_rays.hpp): the Sim's static solids (it must have a ray scene),
/// the timeline's movers and push mode's bodies at the state's time; no balls (the caller adds the agents).
sense::WorldAtInstant world_now(const Sim& sim, const SimState& state);

/// What agent i may use to decide now: its view as the last reset() or step() left it.
inline const AgentView& observe(const SimState& state, int i) { return state.agents[std::size_t(i)].view; }

/// The opponent agent `i` plays against in `state` by the team rule, among the opponents still in the game
/// (or its current one when none is left). Pure: depends on positions and activity only.
int choose_opponent(const SimState& state, int i, OpponentChoice rule);

}  // namespace peg3d::game
