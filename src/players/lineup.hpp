#pragma once
// The policies of every agent of a game, built from the configuration: who plays, with which seed, and
// which FACL agents learn together. A Lineup owns them and hands play() one pointer per agent.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "players/facl_policy.hpp"
#include "game/policy.hpp"

namespace peg3d::players {

/// The seed of agent k of a role whose first agent is seeded with `role_seed` (the first keeps it, so a
/// one-agent role is seeded exactly as before teams existed).
std::uint64_t agent_seed(std::uint64_t role_seed, int k);

/// The FACL models of one role's agents: the distinct models, and which one each agent plays.
struct RoleModels {
  std::vector<std::shared_ptr<FaclModel>> models;  ///< in order of first use
  std::vector<int> of_agent;                       ///< model index of agent k (-1: the agent is not FACL)

  /// The model agent k plays; agents past the trained count play the last agent's. nullptr when none.
  std::shared_ptr<const FaclModel> for_agent(int k) const;
  bool empty() const { return models.empty(); }
};

/// Policies for one game, agent by agent.
class Lineup {
 public:
  void add(std::unique_ptr<game::Policy> policy);
  std::span<game::Policy* const> policies() const { return pointers_; }
  int size() const { return static_cast<int>(pointers_.size()); }
  game::Policy& operator[](int i) const { return *pointers_[std::size_t(i)]; }

 private:
  std::vector<std::unique_ptr<game::Policy>> owned_;
  std::vector<game::Policy*> pointers_;
};

/// Adds policies for `count` agents of `role` as the configuration says: agent k plays
/// config.agent(role, k).policy, seeded by agent_seed(seed, k). FACL agents of the role whose settings are
/// equal share one model and learn together; `models` (when given) receives them.
void add_configured(Lineup& lineup, const game::GameConfig& config, game::Role role, int count, std::uint64_t seed,
                    RoleModels* models = nullptr);

/// Adds greedy FACL policies for `count` agents over trained models (agent k plays models.for_agent(k)).
void add_frozen(Lineup& lineup, const RoleModels& models, int count);

}  // namespace peg3d::players
