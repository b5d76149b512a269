#include "experiment/opponent_pool.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/random.hpp"

namespace peg3d::experiment {

int detail::first_unfit_player(const std::vector<std::string>& names, game::Role role) {
  for (std::size_t k = 0; k < names.size(); ++k) {
    const players::PlayerInfo* p = players::find_player(names[k]);
    if (p == nullptr || !p->plays(role) || p->learns()) return static_cast<int>(k);
  }
  return -1;
}

namespace {

// Whether any agent of `role` learns with FACL under `config`.
bool learns(const game::GameConfig& config, game::Role role) {
  const auto& list = role == game::Role::kPursuer ? config.pursuers : config.evaders;
  if (players::learns(config.agent(role))) return true;
  return std::any_of(list.begin(), list.end(), [](const game::AgentConfig& a) { return players::learns(a); });
}

}  // namespace

OpponentPool::OpponentPool(const std::shared_ptr<const world::Arena>& arena, const game::GameConfig& config,
                           const OpponentPoolConfig& pool, bool enabled)
    : share_(pool.share) {
  if (!enabled) return;
  // The pursuers' opponents (the pool's evaders) first, then the evaders': the order the draws index.
  if (learns(config, game::Role::kPursuer)) {
    for (const std::string& name : pool.evaders) {
      entries_.push_back({game::Role::kPursuer, name, game::Sim(arena, game::with_role_playing(config, game::Role::kEvader, name))});
    }
  }
  if (learns(config, game::Role::kEvader)) {
    for (const std::string& name : pool.pursuers) {
      entries_.push_back({game::Role::kEvader, name, game::Sim(arena, game::with_role_playing(config, game::Role::kPursuer, name))});
    }
  }
}

int OpponentPool::choose(std::uint64_t seed, bool pursuers_learn, bool evaders_learn) const {
  const auto open = [&](const Entry& e) { return e.learner == game::Role::kPursuer ? pursuers_learn : evaders_learn; };
  const auto n = std::count_if(entries_.begin(), entries_.end(), open);
  if (n == 0) return -1;
  // Two uniform draws: one for the share, one for the entry among the open ones.
  Rng rng(seed);
  if (unit_uniform(rng) >= share_) return -1;
  auto k = static_cast<std::ptrdiff_t>(unit_uniform(rng) * static_cast<double>(n));
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    if (open(entries_[i]) && k-- == 0) return static_cast<int>(i);
  }
  return -1;  // unreachable: k < n
}

std::vector<std::string> pool_opponent_names(const OpponentPool& pool, std::span<const int> opponents) {
  std::vector<std::string> names;
  names.reserve(opponents.size());
  for (const int k : opponents) {
    if (k < -1 || k >= static_cast<int>(pool.entries().size())) throw std::logic_error("not an opponent-pool entry");
    names.emplace_back(k < 0 ? "" : pool.entries()[std::size_t(k)].opponent);
  }
  return names;
}

void check_journaled_opponents(const OpponentPool& pool, std::span<const int> opponents, std::size_t episodes) {
  if (opponents.size() != episodes) {
    throw InputError({}, 0, "training_opponent",
                     fmt::format("has {} entries for {} training episodes", opponents.size(), episodes));
  }
  const int entries = static_cast<int>(pool.entries().size());
  for (const int k : opponents) {
    if (k < -1 || k >= entries) {
      throw InputError({}, 0, "training_opponent", fmt::format("{} is neither -1 nor one of the pool's {} entries", k, entries));
    }
  }
}

}  // namespace peg3d::experiment
