#pragma once
// A policy read from a file and played, not learning, whatever trained it: a FACL model (players/policy_io.hpp) or an
// MLP (players/mlp_policy.hpp, trained in Python). Read once and shared read-only by every game and thread that
// plays it, so every program that takes a policy file (peg-matchup, peg-league, peg-collide cases, the Python
// front's opponents) plays both kinds the same way.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "players/facl_policy.hpp"
#include "players/lineup.hpp"
#include "players/mlp_policy.hpp"
#include "game/policy.hpp"

namespace peg3d::players {

struct SavedPolicy {
  std::shared_ptr<const FaclModel> facl;  ///< set for a FACL file
  std::shared_ptr<const MlpModel> mlp;    ///< set for an MLP file
  /// "fnv1a64:..." of the model's canonical JSON (a FACL model's as policy_to_json writes it, an MLP's document)
  std::string content_hash;
  std::filesystem::path file;  ///< where it was read from (its players carry it, for messages)

  /// "facl" or "mlp": the name results give the policy's kind.
  const char* kind_name() const { return facl ? "facl" : "mlp"; }
  /// The agent configuration it must play with (its guard, steering, observation): a FACL model's own; null for
  /// an MLP, which plays with the game's agent configuration (the one its observations were made under).
  const game::AgentConfig* config() const { return facl ? &facl->config() : nullptr; }
  /// A new player of the policy (its per-agent buffers its own, the model shared); `seed` feeds an MLP that
  /// samples its actions ("play": "sample"); every other player is greedy and ignores it.
  std::unique_ptr<game::Policy> make(std::uint64_t seed) const;
  /// Throws PolicyFormatError naming the file unless the policy can play agent `rank` of `role` in `sim`: an MLP's
  /// observation must be the agent's (fit_observation). Programs call it before any run.
  void check_fits(const game::Sim& sim, game::Role role, int rank) const;
  /// check_fits for every agent of `role` in every scenario of the Sim's map.
  void check_fits(const game::Sim& sim, game::Role role) const;
};

/// Reads a policy file of either kind for an agent of `role`. A file that cannot be read, is not a policy
/// document, does not fit or was saved for the other role is a PolicyFormatError (an InputError) naming it.
std::shared_ptr<const SavedPolicy> load_saved_policy(const std::filesystem::path& file, game::Role role);

/// Adds `count` players of `policy` to a line-up, the k-th seeded by agent_seed(seed, k) (as add_configured).
void add_saved(Lineup& lineup, const SavedPolicy& policy, int count, std::uint64_t seed);

}  // namespace peg3d::players
