#pragma once
// A batch of games stepped together, for learners outside the C++ side (the Python front, python/): N
// independent runs of one Sim, each with its own SimState, stepped by one call on T threads. The batch owns
// flat buffers (observations, rewards, flags) that a caller reads in place, without a copy; every step
// overwrites them. Agents can be left to C++ policies (a classic strategy or a saved FACL or MLP policy), which act
// inside the step with no call out per game.
//
// Results depend on the root seed only, never on the thread count: game g's episode e starts from
// derive_seed(seed, {g, e}), its C++ policies are seeded from derive_seed(seed, {g, kPolicyStream, agent}),
// and the threads take fixed slices of the games. A game re-seeded alone (reset_game) plays as game 0 of a
// batch of that seed: derive_seed(its seed, {0, e}), and so does a one-game batch's game.
//
// Autoreset is next-step (Gymnasium's AutoresetMode.NEXT_STEP): the step after a game's episode ended resets
// that game instead of stepping it; its actions are ignored, its rewards are 0 and its flags false.

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "game/episode.hpp"
#include "game/observation.hpp"
#include "game/sim.hpp"
#include "players/lineup.hpp"
#include "players/saved_policy.hpp"

namespace peg3d::env {

/// One member of a mixture of C++ players (BatchSettings::controllers): a policy name (flee, pure-pursuit, ...) or
/// a saved policy file (FACL or MLP), played in the share weight / (the mixture's total weight) of the episodes.
struct MixtureEntry {
  std::string policy;
  double weight = 1.0;  ///< finite, >= 0; the mixture's weights sum to > 0
  bool operator==(const MixtureEntry&) const = default;
};

/// The most members one mixture may have: every game builds a player of each for each of its agents.
inline constexpr int kMaxMixtureEntries = players::kMaxMixtureMembers;

/// How a batch is built. Every field a user sets is validated by Batch (InvalidParameter naming it).
struct BatchSettings {
  int games = 1;                ///< N, in [1, 65536]
  int threads = 1;              ///< T, in [1, 256]; capped at games
  std::uint64_t seed = 0;       ///< root seed
  int neighbours = 2;           ///< k, in [0, 16]: the neighbour slots of each kind in every observation (game/observation.hpp)
  /// The map's scenarios the episodes start from, by name, taking turns: episode e of game g plays the
  /// (g + e) mod count-th, so that the games spread over the starts from their first episode. A name may come
  /// more than once, to play that start more often (for training). They must have the same numbers of pursuers
  /// and evaders (a batch's arrays have one shape). Empty: the map's scenarios with the first one's numbers.
  std::vector<std::string> scenarios;
  /// agent name (pursuer_0, evader_1, ...) or role (pursuer, evader) -> the mixture of C++ players it plays: one
  /// member, or several drawn per episode by weight. Later keys override earlier ones for the agents they name; an
  /// empty mixture (or one member named "") gives the agents back to the caller. The agents of one key draw
  /// together (a team plays one member in an episode), from derive_seed(the game's seed, {game, kMixtureStream,
  /// episode, key}), so a batch's draws depend on its seed only. The others take the caller's actions.
  /// A mixture's FACL files carry their agent configuration (guard, steering, observation, ...): they must carry
  /// the same one, under which its other members play.
  std::vector<std::pair<std::string, std::vector<MixtureEntry>>> controllers;
  /// Keep every instant of game 0's current episode (trace(0)), for replays: the Python front's render().
  bool record = false;
  /// bytes the games may take, > 0; 0: three quarters of the machine's physical memory. A batch whose estimate
  /// (the first game's state as built, its agents' own maps, the arrays of observations) exceeds it is refused
  /// before its games are made, with MemoryBudgetError: N games that do not fit would otherwise fail inside
  /// Bullet or the kernel's out-of-memory killer, not with an error.
  std::size_t memory_budget = 0;
};

/// A batch that would take more memory than its budget (BatchSettings::memory_budget): an input error naming
/// the figures (games, bytes per game, the budget).
class MemoryBudgetError : public InputError {
 public:
  using InputError::InputError;
};

/// Lower and upper bounds of every observation entry on this Sim.
struct ObservationBounds {
  std::vector<float> low, high;
};

class Batch {
 public:
  /// The batch's Sim is built from `arena` and `config`, with every agent played by a saved FACL policy given
  /// that policy's own agent configuration (its guard, steering, observation), as peg-matchup plays it.
  Batch(std::shared_ptr<const world::Arena> arena, game::GameConfig config, BatchSettings settings);
  ~Batch();
  Batch(const Batch&) = delete;
  Batch& operator=(const Batch&) = delete;

  int games() const { return settings_.games; }
  int agents() const { return agents_; }
  int pursuers() const { return pursuers_; }
  /// The length of every agent's row of observations(): the largest agent's observation (game/observation.hpp);
  /// a smaller one's row holds its observation first, then zeros.
  int observation_size() const { return stride_; }
  /// Agent i's observation: its segments (name, offset, size, unit, bounds, meaning), game::observation_table's.
  const game::ObservationTable& observation_table(int i) const { return tables_[std::size_t(i)]; }
  const std::vector<std::string>& agent_names() const { return names_; }
  /// Whether agent i is played on the C++ side (its actions are ignored).
  bool controlled(int i) const { return !mixtures_[std::size_t(i)].empty(); }
  /// The members of agent i's mixture, as given (empty for the caller's agents).
  std::vector<MixtureEntry> mixture(int i) const;
  /// Which member of its mixture agent i plays in game g's current episode: an index into mixture(i), or -1 for
  /// the caller's agents.
  int member(int game, int i) const { return controlled(i) ? games_[std::size_t(game)].member[std::size_t(i)] : -1; }
  /// Agent i's bounds, its observation's size long.
  ObservationBounds observation_bounds(int i) const;
  /// rad: the steering bound per step, the action space's bound on both components.
  double action_bound(game::Role role) const;
  const game::Sim& sim() const { return *sim_; }
  const game::SimState& state(int game) const { return games_[std::size_t(game)].state; }

  /// Starts a new episode in every game; with a seed, first re-seeds the batch (episodes count from 0 again).
  void reset(std::optional<std::uint64_t> seed = std::nullopt);
  /// Starts a new episode in game g alone; with a seed, first re-seeds that game: it then plays exactly as
  /// game 0 of a batch reset with that seed (its episodes count from 0, and take the scenarios in turn from
  /// the first). The other games are left as they are.
  void reset_game(int game, std::optional<std::uint64_t> seed = std::nullopt);
  /// Steps every game once. `actions` holds games x agents x 2 doubles (d_alpha, d_theta), rad; entries of
  /// C++-played agents and of agents out of the game are ignored. Games whose episode ended are reset instead
  /// (autoreset). Throws game::CommandError naming the game (CommandError::game) when a command cannot be
  /// stepped: an action of the caller's is checked (game::check_command) before any policy acts or any game
  /// steps, so the batch is left as it was; a C++-played policy's command is refused by its game's step()
  /// (naming the policy's file), and the games of other threads may have stepped: build a new batch then.
  void step(const double* actions);

  // The buffers, games x agents (x observation_size), rewritten by reset() and step().
  float* observations() { return observations_.data(); }
  float* rewards() { return rewards_.data(); }
  /// 1 where the agent's part in the game ended in the step: its capture, the last capture, a terminating
  /// collision.
  std::uint8_t* terminated() { return terminated_.data(); }
  std::uint8_t* truncated() { return truncated_.data(); }  ///< 1 where the time limit ended the game
  std::uint8_t* acted() { return acted_.data(); }          ///< 1 where the agent was in the game at the step's start
  std::uint8_t* active() { return active_.data(); }        ///< 1 where the agent is in the game after the step
  std::uint8_t* collided() { return collided_.data(); }    ///< 1 where it hit an obstacle or agent in the step
  std::uint8_t* captured() { return captured_.data(); }    ///< 1 where it was captured in the step (evaders)
  /// The step's reward terms per agent: obstacle, target, success (unweighted; RewardTerms).
  float* reward_terms() { return terms_.data(); }
  /// 1 where the game was reset by the step (autoreset) or by reset().
  std::uint8_t* reset_flags() { return reset_flags_.data(); }
  /// The state vector of game g for centralised critics: per agent position (3), alpha, theta, active; then time.
  std::vector<float> global_state(int game) const;
  int global_state_size() const { return agents_ * 6 + 1; }
  /// Lower and upper bounds of every global_state entry: positions within the arena's box, alpha in [-pi, pi],
  /// theta in [0, pi], active in [0, 1], time in [0, time_limit + dt] (the last step may pass the limit).
  ObservationBounds state_bounds() const;
  long long episode(int game) const { return games_[std::size_t(game)].episode; }
  /// Every instant of game 0's current episode so far when settings.record (null otherwise, and for other games).
  const game::Trace* trace(int game) const { return games_[std::size_t(game)].trace.get(); }
  /// The names of the scenarios the episodes start from, in the order they take turns (BatchSettings::scenarios).
  std::vector<std::string> scenario_names() const;

 private:
  struct Game {
    explicit Game(const game::Sim& sim) : state(sim) {}
    game::SimState state;
    // Per agent, a player of every member of its mixture (none for the caller's agents), the member it plays
    // this episode, and that player (null for the caller's agents).
    std::vector<std::vector<std::unique_ptr<game::Policy>>> players;
    std::vector<int> member;
    std::vector<game::Policy*> policies;
    std::vector<Steering> commands;
    long long episode = 0;
    // The root seed of its episodes and policies, and the game number they are derived with: the batch's seed
    // and the game's index, or, once re-seeded alone, its own seed and 0.
    std::uint64_t seed = 0, slot = 0;
    std::unique_ptr<game::Trace> trace;  // settings.record, game 0 only
  };
  const world::Scenario& scenario_for(int game, long long episode) const;
  void start_episode(int g);
  void step_game(int g, const double* actions);
  /// game::step of game g, a refused command's error naming the game (and a C++-played policy's file).
  const game::StepEvents& step_or_name(int g);
  void write_outputs(int g);
  void build_policies(int g);
  /// Draws each mixture's member for game g's current episode and points its agents' policies at them.
  void choose_members(int g);
  /// Refuses the batch (MemoryBudgetError) when its games would take more than settings_.memory_budget: estimated
  /// from the first game's `state_bytes` (what malloc gave for building it), before the others are made.
  void check_memory_budget(std::size_t state_bytes) const;
  void run_on_threads(void (Batch::*work)(int, const double*), const double* actions);

  std::shared_ptr<const game::Sim> sim_;
  BatchSettings settings_;
  std::vector<game::ObservationTable> tables_;  // per agent
  int stride_ = 0;                              // the largest table's size
  std::vector<int> scenarios_;  // indices into the map's scenarios
  int agents_ = 0, pursuers_ = 0;
  std::vector<std::string> names_;
  // How a C++-played agent plays: a classic strategy, or a model read once from its file and shared, read-only,
  // by every game's policy; with its weight in the agent's mixture (a mixture file's members are the same).
  using Member = players::SavedPolicy::Member;
  Member resolve_member(int agent, const MixtureEntry& entry, const std::string& field) const;
  // Per agent: its mixture's members (empty: the caller's agent), and which key of settings_.controllers gave it
  // (the agents of one key draw together).
  std::vector<std::vector<Member>> mixtures_;
  std::vector<std::vector<double>> weights_;  // per agent, its mixture's weights (players::draw_member's)
  std::vector<int> mixture_key_;
  std::vector<Game> games_;
  std::vector<float> observations_, rewards_, terms_;
  std::vector<std::uint8_t> terminated_, truncated_, acted_, active_, collided_, captured_, reset_flags_;

  // A fixed pool of threads - 1 workers; the caller's thread takes slice 0.
  struct Pool;
  std::unique_ptr<Pool> pool_;
};

}  // namespace peg3d::env
