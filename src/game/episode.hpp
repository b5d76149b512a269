#pragma once
// Whole episodes played by policies: a thin loop over step() (game/sim.hpp). Every step each agent still in
// the game acts on its view, step() moves the world, and, when learning, each agent's policy learns from its
// reward and its next view. The episode's figures (EpisodeResult) and, on request, every step (Trace) are
// read from the state and the step events; nothing here plays the game beside step().

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "game/policy.hpp"
#include "game/sim.hpp"

namespace peg3d::game {

/// The figures of one episode. For several agents of a role, paths, returns and pinned fractions are means
/// per agent of the role (with one of each they are that agent's), so results of different team sizes
/// compare.
struct EpisodeResult {
  Outcome outcome = Outcome::kTimeout;
  int steps = 0;
  double duration = 0.0;        ///< s
  double final_distance = 0.0;  ///< m, the smallest pursuer-evader distance at the end among evaders in the game during the last step
  double pursuer_path = 0.0;    ///< m travelled, mean per pursuer
  double evader_path = 0.0;     ///< m travelled, mean per evader
  int collisions = 0;           ///< collision events of all agents
  int contact_give_ups = 0;     ///< mover contact searches that gave up and answered conservatively (StepEvents)
  std::optional<CollisionEvent> first_collision;
  double pursuer_return = 0.0;  ///< undiscounted sum of rewards, mean per pursuer
  double evader_return = 0.0;   ///< likewise per evader
  int pursuer_pinned_steps = 0;  ///< agent-steps ending with a pursuer's centre within max(radius, 0.1 m) of a face
  int evader_pinned_steps = 0;
  int pursuer_agent_steps = 0;   ///< agent-steps of pursuers in the game
  int evader_agent_steps = 0;
  int pursuers = 1;              ///< agents of each role
  int evaders = 1;
  int captures = 0;              ///< evaders captured
  double capture_time_sum = 0.0;   ///< s, sum over captured evaders of their capture times
  double last_capture_time = 0.0;  ///< s, time of the last capture (0 when none)

  /// Every evader captured.
  bool captured() const { return outcome == Outcome::kCapture; }
  /// Share of the role's agent-steps spent pinned against the arena's faces.
  double pinned_fraction(Role r) const {
    const int pinned = r == Role::kPursuer ? pursuer_pinned_steps : evader_pinned_steps;
    const int steps = r == Role::kPursuer ? pursuer_agent_steps : evader_agent_steps;
    return steps > 0 ? static_cast<double>(pinned) / steps : 0.0;
  }
};

/// The episode's figures, read from a state (normally a done one).
EpisodeResult summarize(const SimState& state);

/// One agent's figures over an episode.
struct AgentSummary {
  Role role = Role::kPursuer;
  int rank = 0;                 ///< index among its role
  double path = 0.0;            ///< m
  double total_reward = 0.0;    ///< undiscounted return
  int steps = 0;                ///< steps in the game
  double pinned_fraction = 0.0; ///< share of its steps pinned against a face
  int collisions = 0;
  int captures = 0;             ///< evaders captured (pursuers)
  double captured_at = -1.0;    ///< s, its capture time (evaders); < 0 when never captured
};

/// Every agent's figures, in agent order.
std::vector<AgentSummary> agent_summaries(const SimState& state);

/// One agent at one instant of a recorded episode.
struct AgentFrame {
  KinematicState state;
  Percept percept;
  Steering command;     ///< what it was told to do in the step ending here (zero at the start)
  double reward = 0.0;  ///< its reward for the step ending here
  bool active = true;   ///< in the game at this instant
  /// With limited sight (AgentConfig::sight): the opponent of its view at this instant (-1: full information, and
  /// the two fields after it unused), whether it saw it, and where it took it to be.
  int opponent = -1;
  bool sees = true;
  Vec3 estimate = Vec3::Zero();
};

/// A cell of an agent's own map that became occupied or free at a frame (Trace::map_flips).
struct MapFlip {
  int frame = 0;
  int agent = 0;
  Vec3 centre = Vec3::Zero();  ///< m, the cell's centre
  bool occupied = false;
};

/// Every instant of one episode, for trajectory files, replays and viewers. Frame 0 is the start; frame k
/// follows step k. reserve() makes recording allocation-free.
struct Trace {
  int agents = 0;
  std::vector<Role> roles;                 ///< per agent
  std::vector<double> times;               ///< s, per frame
  std::vector<AgentFrame> frames;          ///< frame-major: frames[k * agents + i]
  std::vector<CollisionEvent> collisions;  ///< every collision, in order
  std::vector<CaptureEvent> captures;      ///< every capture, in order
  std::vector<PushEvent> pushes;           ///< push mode: every push, in order
  /// Push mode: every mover's pose at every frame, frame-major (body_poses[k * movers + m]); empty otherwise
  /// (the shared timeline has them).
  std::vector<Pose> body_poses;
  int movers = 0;                          ///< movers per frame of body_poses
  /// Sensing (all empty when no agent carries a sensor), laid out as SimState::sensing lays it out: agent i carries
  /// slots [slot_first[i], slot_first[i + 1]) (one per sensor, in order); slot s's values are [value_first[s],
  /// value_first[s + 1]) of a frame's readings.
  std::vector<int> slot_first;
  std::vector<int> value_first;
  std::vector<float> readings;        ///< frame-major: value v of frame k at k * values() + v (m for ranges)
  std::vector<std::uint8_t> echoes;   ///< 1 where that value is an echo
  std::vector<int> scan_frames;       ///< frame-major, per slot: the frame whose pose its reading was taken at
  /// The agents' own maps: every cell occupied at frame 0, then every change of a cell's occupancy, in order.
  std::vector<MapFlip> map_flips;

  /// Makes recording an episode of at most max_steps steps allocation-free: its frames, `values` readings a frame
  /// (every agent's sensors together), and `map_flips` changes of the agents' maps (beyond that they grow).
  void reserve(int max_steps, int agent_count, int values = 0, std::size_t map_flip_count = 0);
  /// reserve() for an episode of `scenario` in `sim`: its frames and every reading its agents' sensors take.
  void reserve(const Sim& sim, const world::Scenario& scenario, std::size_t map_flip_count = 0);
  void clear();
  int frame_count() const { return static_cast<int>(times.size()); }
  int values() const { return value_first.empty() ? 0 : value_first.back(); }  ///< readings per frame
  /// Sensors agent i carries (slots).
  int sensors(int i) const { return slot_first.empty() ? 0 : slot_first[std::size_t(i) + 1] - slot_first[std::size_t(i)]; }
  /// Agent i's k-th sensor's readings over the episode, frame-major, as a sensor's replay takes them.
  struct SlotReadings {
    int size = 0;
    std::vector<float> values;
    std::vector<std::uint8_t> echo;
    std::vector<int> scan_frames;
    sense::RecordedReadings view(int frames) const { return {frames, size, values, echo, scan_frames}; }
  };
  SlotReadings slot_readings(int i, int k) const;
  const AgentFrame& at(int frame, int agent) const { return frames[std::size_t(frame) * std::size_t(agents) + std::size_t(agent)]; }
  /// Appends the state's current instant (after reset(): the start; after step(): with the step's events).
  void record(const SimState& state, bool after_step);

 private:
  void record_sensing(const SimState& state, bool after_step);
};

/// The label of agent i of a trace (agent_label: "pursuer_0", "evader_0", ...).
std::string agent_label(const Trace& trace, int i);

/// step(), with a CommandError for an agent whose policy (policies[i] drives agent i) was read from a file
/// naming that file (CommandError::played_by).
const StepEvents& step_naming_file(const Sim& sim, SimState& state, std::span<const Steering> commands,
                                   std::span<Policy* const> policies);

/// Starts `policy`, which drives agent i, on the episode `state` was just reset to: its begin_episode, then, for a
/// classic player (Policy::scripted), the agent's configuration without the motion space (Sim::scripted_config), so
/// that a classic player plays the same game in every loop, drawn from a mixture or not. Every loop starts its
/// policies with it.
void begin_playing(const Sim& sim, SimState& state, int i, Policy& policy, bool learning);

/// Plays one episode of `scenario`. policies[i] drives agent i (pursuers first, then evaders, in the
/// scenario's order); distinct agents need distinct policy objects (they may share a FACL model). With
/// `learning`, policies explore and learn after every step. `trace`, when given, receives every instant
/// (reserve it to keep the loop allocation-free).
EpisodeResult play(const Sim& sim, SimState& state, const world::Scenario& scenario, std::span<Policy* const> policies,
                   bool learning, std::uint64_t seed, Trace* trace = nullptr);

/// A policy that replays fixed steering commands, one per step (then zero): a recorded trajectory or a
/// scripted motion driving one agent through play() like any policy.
class CommandScript final : public Policy {
 public:
  explicit CommandScript(std::vector<Steering> commands) : commands_(std::move(commands)) {}
  void begin_episode(const AgentView&, bool) override { next_ = 0; }
  Steering act(const AgentView&) override { return next_ < commands_.size() ? commands_[next_++] : Steering{}; }

 private:
  std::vector<Steering> commands_;
  std::size_t next_ = 0;
};

/// A steering command that holds from a time on.
struct TimedCommand {
  double time = 0.0;  ///< s, from when it applies (until the next command's time)
  Steering command;   ///< rad per step, as any policy requests it
};

/// A policy that plays piecewise-constant steering commands by game time: at each step the last command whose
/// time has come (none yet: no turn).
class TimedCommands final : public Policy {
 public:
  /// `commands` sorted by time.
  explicit TimedCommands(std::vector<TimedCommand> commands) : commands_(std::move(commands)) {}
  Steering act(const AgentView& view) override;

 private:
  std::vector<TimedCommand> commands_;
};

/// A point to fly to; with a time, it becomes the target at that time, else once the one before is reached.
struct Waypoint {
  Vec3 point = Vec3::Zero();
  double time = -1.0;  ///< s; < 0: when the agent has come within one step of the previous waypoint
};

/// A policy that flies its agent at its speed towards one waypoint after the other (turning as fast as the
/// steering bound allows); after the last it holds its heading.
class WaypointFollower final : public Policy {
 public:
  explicit WaypointFollower(std::vector<Waypoint> waypoints) : waypoints_(std::move(waypoints)) {}
  void begin_episode(const AgentView&, bool) override { next_ = 0; }
  Steering act(const AgentView& view) override;

 private:
  std::vector<Waypoint> waypoints_;
  std::size_t next_ = 0;
};

}  // namespace peg3d::game
