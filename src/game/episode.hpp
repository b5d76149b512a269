#pragma once
// One pursuit-evasion episode in an Arena. The Arena is shared and read-only; everything an episode changes
// lives in the Game (its CollisionWorld scratch) and the EpisodeState. Each step, at dt:
//   both agents observe -> act -> steer (bounded) -> motion space -> move (clamped to the arena)
//   -> swept collision check -> capture check -> observe again -> rewards -> learn.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "game/game_config.hpp"
#include "game/percept.hpp"
#include "game/policy.hpp"
#include "world/arena.hpp"
#include "world/collision_world.hpp"

namespace peg3d::game {

enum class Outcome {
  kCapture,           ///< d_PE <= capture_distance at the end of a step
  kTimeout,           ///< time_limit reached
  kPursuerCollision,  ///< the pursuer hit an obstacle (CollisionMode::kTerminate)
  kEvaderCollision,   ///< the evader hit an obstacle (CollisionMode::kTerminate)
};
const char* to_string(Outcome o);

/// An agent touching an obstacle.
struct CollisionEvent {
  double time = 0.0;                      ///< s, time of impact within the episode
  Role agent = Role::kPursuer;
  world::ObstacleKind kind = world::ObstacleKind::kSphere;
  int obstacle_id = -1;                   ///< index in the map's list of that kind
  Vec3 point = Vec3::Zero();              ///< m, contact point
  double fraction = 0.0;                  ///< time of impact as a fraction of the step, [0, 1]
  double penetration = 0.0;               ///< m, overlap depth when already intersecting
};

/// The small changing state of an episode.
struct EpisodeState {
  KinematicState pursuer;
  KinematicState evader;
  double time = 0.0;  ///< s
  int step = 0;
};

struct EpisodeResult {
  Outcome outcome = Outcome::kTimeout;
  int steps = 0;
  double duration = 0.0;        ///< s
  double final_distance = 0.0;  ///< m, d_PE at the end
  double pursuer_path = 0.0;    ///< m travelled
  double evader_path = 0.0;     ///< m travelled
  int collisions = 0;           ///< collision events of both agents
  std::optional<CollisionEvent> first_collision;
  double pursuer_return = 0.0;  ///< undiscounted sum of rewards
  double evader_return = 0.0;
  int pursuer_pinned_steps = 0;  ///< steps ending with the centre within max(radius, 0.1 m) of a face
  int evader_pinned_steps = 0;

  bool captured() const { return outcome == Outcome::kCapture; }
  double pinned_fraction(Role r) const {
    return steps > 0 ? static_cast<double>(r == Role::kPursuer ? pursuer_pinned_steps : evader_pinned_steps) / steps : 0.0;
  }
};

/// One step as recorded for trajectory files (index 0 is the start, before any action).
struct StepRecord {
  double time = 0.0;
  KinematicState pursuer, evader;
  Percept pursuer_percept, evader_percept;
  Steering pursuer_steering, evader_steering;  ///< what each policy requested for the step ending here
  double pursuer_reward = 0.0, evader_reward = 0.0;
};

/// A pairing of two agents on an arena.
class Game {
 public:
  /// Validates the configuration (throws InvalidParameter).
  Game(std::shared_ptr<const world::Arena> arena, const GameConfig& config);

  const GameConfig& config() const { return config_; }
  const world::Arena& arena() const { return *arena_; }

  /// The start of a scenario: its positions (kept radius inside the arena) and headings (the scenario's, or
  /// the configured InitialHeading; kRandom draws from `seed`). Throws std::runtime_error when an agent
  /// starts overlapping an obstacle.
  EpisodeState start(const world::Scenario& scenario, std::uint64_t seed);

  /// Plays one episode. With `learning`, policies explore and learn after every step. `trace`, when given,
  /// receives every step (reserve max_steps() + 1 to keep the loop allocation-free).
  EpisodeResult play(const world::Scenario& scenario, Policy& pursuer, Policy& evader, bool learning,
                     std::uint64_t seed, std::vector<StepRecord>* trace = nullptr);

 private:
  AgentView view(Role role, const EpisodeState& s) const;
  Heading next_heading(Role role, const EpisodeState& s, const AgentView& v, const Steering& u) const;

  std::shared_ptr<const world::Arena> arena_;
  GameConfig config_;
  world::CollisionWorld collisions_;
  int pursuer_body_ = -1, evader_body_ = -1;
};

}  // namespace peg3d::game
