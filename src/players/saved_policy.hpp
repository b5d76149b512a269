#pragma once
// A policy read from a file and played, not learning, whatever trained it: a FACL model (players/policy_io.hpp) or an
// MLP (players/mlp_policy.hpp, trained in Python). Read once and shared read-only by every game and thread that
// plays it, so every program that takes a policy file (peg-matchup, peg-league, peg-collide cases, the Python
// front's opponents) plays both kinds the same way.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "players/facl_policy.hpp"
#include "players/lineup.hpp"
#include "players/mlp_policy.hpp"
#include "game/game_config.hpp"
#include "game/policy.hpp"

namespace peg3d::players {

/// The most members one mixture may have (a peg3d-mixture file, or a batch's opponents): every game builds a
/// player of each for each agent that plays it.
inline constexpr int kMaxMixtureMembers = 256;

struct SavedPolicy {
  /// A member of a mixture file: a classic player by name, or a policy file (FACL or MLP), with its weight.
  struct Member {
    std::string player;                         ///< a classic player of the registry; empty for a file
    std::shared_ptr<const SavedPolicy> saved;   ///< a policy file
    double weight = 1.0;                        ///< finite, >= 0; the members' weights sum to > 0
  };
  std::shared_ptr<const FaclModel> facl;  ///< set for a FACL file
  std::shared_ptr<const MlpModel> mlp;    ///< set for an MLP file
  /// Set for a mixture file ("format": "peg3d-mixture", what peg3d.selfplay ships): one member drawn per episode
  /// with probability weight / total, the same member for every agent of a team (make's team_seed).
  std::vector<Member> members;
  /// "fnv1a64:..." of the model's canonical JSON (a FACL model's as policy_to_json writes it, an MLP's document)
  std::string content_hash;
  std::filesystem::path file;  ///< where it was read from (its players carry it, for messages)

  /// "facl", "mlp" or "mixture": the name results give the policy's kind.
  const char* kind_name() const { return facl ? "facl" : mlp ? "mlp" : "mixture"; }
  /// The agent configuration it must play with (its guard, steering, observation): a FACL model's own, or a
  /// mixture's FACL members' (one configuration, checked when read); null for an MLP, which plays with the game's
  /// agent configuration (the one its observations were made under), and for a mixture without FACL members.
  const game::AgentConfig* config() const;
  /// A new player of the policy (its per-agent buffers its own, the model shared); `seed` feeds an MLP that
  /// samples its actions ("play": "sample"); every other player is greedy and ignores it. `agent` and `role`:
  /// the configuration and role of the agent it plays, which a mixture's classic members are made with;
  /// `team_seed`: a mixture's draws, episode e's from derive_seed(team_seed, {e}), so agents given the same one
  /// play the same member in every episode.
  std::unique_ptr<game::Policy> make(std::uint64_t seed, const game::AgentConfig& agent, game::Role role,
                                     std::uint64_t team_seed) const;
  /// Throws PolicyFormatError naming the file unless the policy can play agent `rank` of `role` in `sim`: an MLP's
  /// observation must be the agent's (fit_observation). Programs call it before any run.
  void check_fits(const game::Sim& sim, game::Role role, int rank) const;
  /// check_fits for every agent of `role` in every scenario of the Sim's map.
  void check_fits(const game::Sim& sim, game::Role role) const;
};

/// What is wrong with a mixture's members (a peg3d-mixture file's, or a batch's opponents'), found by the one check
/// both use: a weight not finite or negative (`member`, "weight"), weights that do not sum to a finite number > 0
/// (member -1), or FACL files of differing agent configurations (`member`, "policy"). Each caller throws its own
/// error, naming its own field. (A file's member may not be a mixture; a batch's opponent may be a mixture file.)
struct MixtureProblem {
  int member = -1;      ///< the member at fault; -1: the mixture as a whole
  std::string field;    ///< "weight", "policy" or "" (the whole)
  std::string message;
};
/// The first problem of `members` in their order, or none (message empty).
MixtureProblem check_mixture(std::span<const SavedPolicy::Member> members);
/// The agent configuration a checked mixture's FACL members carry (one for all), or null when it has none.
const game::AgentConfig* mixture_config(std::span<const SavedPolicy::Member> members);

/// Which member a mixture of `weights` (finite, >= 0, summing to > 0) plays for 64 random `bits`: the member whose
/// share of the cumulative weights holds bits' uniform in [0, 1); never one of weight 0.
int draw_member(std::span<const double> weights, std::uint64_t bits);

/// Reads a policy file of any kind (FACL, MLP, mixture) for an agent of `role`. A file that cannot be read, is not a
/// policy document, does not fit or was saved for the other role is a PolicyFormatError (an InputError) naming it;
/// a mixture's members are read relative to its folder, and a bad one is named by its field (members.K.policy).
std::shared_ptr<const SavedPolicy> load_saved_policy(const std::filesystem::path& file, game::Role role);

/// Adds `count` players of `policy` to a line-up for agents 0.. of `role` in a game of `config`, the k-th seeded
/// by agent_seed(seed, k) (as add_configured); a mixture's team draws from `seed`.
void add_saved(Lineup& lineup, const SavedPolicy& policy, const game::GameConfig& config, game::Role role, int count,
               std::uint64_t seed);

}  // namespace peg3d::players
