#include "experiment/training.hpp"

#include <utility>

#include "core/random.hpp"

namespace peg3d::experiment {
namespace {

// Whether any agent of `role` learns with FACL under `config`.
bool learns(const game::GameConfig& config, game::Role role) {
  const auto& list = role == game::Role::kPursuer ? config.pursuers : config.evaders;
  const auto& all = role == game::Role::kPursuer ? config.pursuer : config.evader;
  if (all.policy == game::PolicyKind::kFacl) return true;
  for (const auto& a : list)
    if (a.policy == game::PolicyKind::kFacl) return true;
  return false;
}

}  // namespace

OpponentPool::OpponentPool(const std::shared_ptr<const world::Arena>& arena, const game::GameConfig& config)
    : training_(config.training) {
  if (training_.procedure != game::TrainingProcedure::kOpponentPool) return;
  const std::pair<bool, game::PolicyKind> evaders[] = {{training_.pool_flee, game::PolicyKind::kFlee},
                                                       {training_.pool_flee_apollonius, game::PolicyKind::kFleeApollonius},
                                                       {training_.pool_random, game::PolicyKind::kRandom}};
  const std::pair<bool, game::PolicyKind> pursuers[] = {
      {training_.pool_pure_pursuit, game::PolicyKind::kPurePursuit},
      {training_.pool_pn, game::PolicyKind::kProportionalNavigation},
      {training_.pool_apollonius, game::PolicyKind::kApollonius}};
  if (learns(config, game::Role::kPursuer)) {
    for (const auto& [chosen, kind] : evaders)
      if (chosen) entries_.push_back({game::Role::kPursuer, kind, game::Sim(arena, game::with_role_playing(config, game::Role::kEvader, kind))});
  }
  if (learns(config, game::Role::kEvader)) {
    for (const auto& [chosen, kind] : pursuers)
      if (chosen) entries_.push_back({game::Role::kEvader, kind, game::Sim(arena, game::with_role_playing(config, game::Role::kPursuer, kind))});
  }
}

int OpponentPool::choose(std::uint64_t seed) const {
  if (entries_.empty()) return -1;
  // Two uniform draws, each from the top 53 bits of one output (portable, unlike the std distributions): one
  // for the share, one for the entry.
  Rng rng(seed);
  const auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  if (uniform() >= training_.pool_share) return -1;
  return static_cast<int>(uniform() * static_cast<double>(entries_.size()));
}

}  // namespace peg3d::experiment
