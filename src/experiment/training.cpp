#include "experiment/training.hpp"

#include <cassert>
#include <memory>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/random.hpp"
#include "experiment/progress_reporter.hpp"

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

std::uint64_t stream_seed(std::uint64_t trial_seed, TrialStream s) {
  return derive_seed(trial_seed, {static_cast<std::uint64_t>(s)});
}

void train_lineup(const game::Sim& sim, const OpponentPool* pool, game::Lineup& lineup, int pursuers,
                  std::span<const world::Scenario> scenarios, std::uint64_t seed, int episodes, const StopCheck& stop,
                  ProgressReporter* progress, game::SimState& state, std::vector<game::EpisodeResult>& results,
                  std::vector<int>& opponents) {
  if (sim.config().training.procedure != game::TrainingProcedure::kCoLearning && pool == nullptr) {
    throw std::logic_error("train_lineup: the configuration trains with an opponent pool, but none was given");
  }
  const int evaders = lineup.size() - pursuers;
  const auto stream = [seed](TrialStream s, std::size_t i) {
    return derive_seed(seed, {static_cast<std::uint64_t>(s), static_cast<std::uint64_t>(i)});
  };
  results.reserve(results.size() + static_cast<std::size_t>(episodes));
  opponents.reserve(opponents.size() + static_cast<std::size_t>(episodes));
  // Pool episodes: the learning role's FACL policies (the same objects, so learning carries on) beside the
  // pool entry's classic policies, built on first use.
  const auto entries = pool != nullptr ? pool->entries() : std::span<const OpponentPool::Entry>{};
  std::vector<std::unique_ptr<game::Lineup>> classic(entries.size());
  std::vector<game::Policy*> playing;
  playing.reserve(std::size_t(lineup.size()));
  for (int e = 0; e < episodes; ++e) {
    throw_if_stopped(stop);
    const world::Scenario& scenario = scenarios[std::size_t(e) % scenarios.size()];
    const int p = static_cast<int>(scenario.pursuers.size()), q = static_cast<int>(scenario.evaders.size());
    assert(p <= pursuers && q <= evaders);
    const int k = entries.empty() ? -1 : pool->choose(stream(TrialStream::kTrainingOpponent, std::size_t(e)));
    playing.clear();
    const game::Sim* played = &sim;
    if (k < 0) {
      for (int i = 0; i < p; ++i) playing.push_back(&lineup[i]);
      for (int j = 0; j < q; ++j) playing.push_back(&lineup[pursuers + j]);
    } else {
      const OpponentPool::Entry& entry = entries[std::size_t(k)];
      played = &entry.sim;
      const bool pursuers_learn = entry.learner == game::Role::kPursuer;
      auto& opponent = classic[std::size_t(k)];
      if (!opponent) {
        opponent = std::make_unique<game::Lineup>();
        game::add_configured(*opponent, entry.sim.config(), pursuers_learn ? game::Role::kEvader : game::Role::kPursuer,
                             pursuers_learn ? evaders : pursuers, stream(TrialStream::kPoolOpponents, std::size_t(k)));
      }
      for (int i = 0; i < p; ++i) playing.push_back(pursuers_learn ? &lineup[i] : &(*opponent)[i]);
      for (int j = 0; j < q; ++j) playing.push_back(pursuers_learn ? &(*opponent)[j] : &lineup[pursuers + j]);
    }
    results.push_back(game::play(*played, state, scenario, playing, /*learning=*/true,
                                 stream(TrialStream::kTrainingEpisode, std::size_t(e))));
    opponents.push_back(k);
    if (progress) progress->episode_done();
  }
}

std::vector<std::string> pool_opponent_names(const OpponentPool& pool, std::span<const int> opponents) {
  std::vector<std::string> names;
  names.reserve(opponents.size());
  for (const int k : opponents) {
    if (k < -1 || k >= static_cast<int>(pool.entries().size())) throw std::logic_error("not an opponent-pool entry");
    names.emplace_back(k < 0 ? "" : game::to_string(pool.entries()[std::size_t(k)].opponent));
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
