#pragma once
// A policy steers one agent. The game calls, per step, act() with what the agent sees now and, when the
// agent learns, learn() with the reward of that step and what it sees after it. Policies never touch the
// world or the other agent's state beyond the view they are given.

#include <filesystem>
#include <limits>
#include <span>

#include "game/game_config.hpp"
#include "game/percept.hpp"
#include "geometry/kinematics.hpp"
#include "sense/segment.hpp"
#include "sense/sensor.hpp"

namespace peg3d::game {

/// What an agent with limited sight can test of the space about it (game/knowledge.hpp): whether a straight segment
/// is clear of the solids it knows, the map's terrain and obstacles and the movers where they are now. The
/// partial game's scripted players look for hiding places with it.
class SightProbe {
 public:
  virtual ~SightProbe() = default;
  /// Whether the segment from a to b meets no terrain, obstacle or mover now (agents do not count).
  virtual bool clear(const Vec3& a, const Vec3& b) const = 0;
  /// Whether the agent's own map (AgentConfig::map) has seen the cell holding p, free or occupied; false
  /// without a map.
  virtual bool mapped(const Vec3& p) const {
    (void)p;
    return false;
  }
  /// m from p to the nearest solid it knows (the distance field's shapes and the movers now), at most the field's
  /// cap (world::Arena::max_distance); the arena's faces do not count. Infinite for a probe that knows no solids.
  virtual double clearance(const Vec3& p) const {
    (void)p;
    return std::numeric_limits<double>::infinity();
  }
};

struct ObservationTable;

/// An agent's observation as learners outside the C++ side see it (game/observation.hpp), written on request: the
/// one function the batch of the Python front and the C++ players of networks trained there share.
class ObservationWriter {
 public:
  virtual ~ObservationWriter() = default;
  /// Agent `agent`'s observation now, as `table` (bound to that agent: bind) lays it out, into `out`.
  virtual void write(int agent, const ObservationTable& table, std::span<float> out) const = 0;
  /// The table of agent `agent` that reads what `recorded` lists (game::bind_observation).
  virtual ObservationTable bind(int agent, std::span<const sense::Segment> recorded) const = 0;
  /// The model the agents play in (its game::Sim): a table bound in one stays good while it is the same.
  virtual const void* model() const = 0;
};

/// Everything an agent may use to decide, at one instant.
struct AgentView {
  Role role = Role::kPursuer;
  int index = 0;             ///< the agent's index in the game (pursuers first, then evaders)
  int opponent = -1;         ///< index of the opponent `other` describes
  KinematicState self;
  /// Its team as it is now, itself included, in the order of their ranks (pursuers or evaders in index order):
  /// teammates share where they are. Valid until the state's next step or reset.
  std::span<const KinematicState> team;
  int rank = 0;              ///< its place in `team`
  /// The opponent it plays against (game/sim.hpp, choose_opponent): its state, or with limited sight
  /// (AgentConfig::sight) the agent's estimate of it (SimState::known_state).
  KinematicState other;
  bool other_visible = true;  ///< the opponent is in sight now (always with full information)
  double other_age = 0.0;     ///< s, how old the sighting `other` comes from is (0 while in sight)
  /// With limited sight and the world's obstacles (observation.obstacles = world): the state's probe, valid until
  /// its next step or reset; null otherwise.
  const SightProbe* probe = nullptr;
  double self_speed = 0.0;   ///< m/s
  double other_speed = 0.0;  ///< m/s
  double dt = 0.1;           ///< s
  double time = 0.0;         ///< s, the game time of this view
  Percept percept;
  ObstacleSense field;       ///< the map's nearest obstacle as the distance field reports it (no boundary)
  Box arena;                 ///< the arena box (the agent's centre stays radius inside it)
  /// Its own sensors' latest readings, in the order it carries them (sense/sensor.hpp; each names its sensor):
  /// valid until the state's next step or reset.
  std::span<const sense::Reading> sensors;
  /// Writes its observation as the Python front's batch does (game/observation.hpp); valid like `sensors`.
  const ObservationWriter* observation = nullptr;
};

class Policy {
 public:
  virtual ~Policy() = default;
  /// Called before the first act() of an episode; `learning` says whether learn() will follow each act().
  virtual void begin_episode(const AgentView& view, bool learning) {
    (void)view;
    (void)learning;
  }
  /// The requested heading change for this step (rad); the game clamps it to the steering bound and
  /// applies the motion space.
  virtual Steering act(const AgentView& view) = 0;
  /// The reward of the step just taken and the view after it; `terminal` when that view ends the episode
  /// (capture or a terminating collision; not the time limit, which truncates).
  virtual void learn(double reward, const AgentView& next, bool terminal) {
    (void)reward;
    (void)next;
    (void)terminal;
  }

  /// The policy file this player plays, when it was read from one, so that errors can name it; empty for a
  /// policy made in code.
  const std::filesystem::path& file() const { return file_; }
  void set_file(std::filesystem::path file) { file_ = std::move(file); }

  /// Whether it is a classic (scripted) player this episode, which the game plays free of its agent's motion space
  /// (scripted_agent, begin_playing). Read after begin_episode: a mixture's answer is its member's of the episode.
  virtual bool scripted() const { return false; }

 private:
  std::filesystem::path file_;
};

}  // namespace peg3d::game
