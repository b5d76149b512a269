#include "experiment/training.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/random.hpp"
#include "experiment/progress_reporter.hpp"
#include "game/random_start.hpp"

namespace peg3d::experiment {
namespace {

// How many of `episodes` training episodes a role with learning share `share` learns in (at least one).
int learning_episodes(double share, int episodes) {
  return share >= 1.0 ? episodes : std::max(1, static_cast<int>(std::ceil(share * static_cast<double>(episodes))));
}

// Whether any agent of `role` learns with FACL under `config`.
bool learns(const game::GameConfig& config, game::Role role) {
  const auto& list = role == game::Role::kPursuer ? config.pursuers : config.evaders;
  const auto& all = role == game::Role::kPursuer ? config.pursuer : config.evader;
  if (all.policy == game::PolicyKind::kFacl) return true;
  for (const auto& a : list)
    if (a.policy == game::PolicyKind::kFacl) return true;
  return false;
}

// A learning policy whose role's training is over: it plays its policy greedily and learns nothing.
class Resting final : public game::Policy {
 public:
  explicit Resting(game::Policy& policy) : policy_(&policy) {}
  void begin_episode(const game::AgentView& view, bool) override { policy_->begin_episode(view, false); }
  Steering act(const game::AgentView& view) override { return policy_->act(view); }

 private:
  game::Policy* policy_;
};

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

int OpponentPool::choose(std::uint64_t seed, bool pursuers_learn, bool evaders_learn) const {
  const auto open = [&](const Entry& e) { return e.learner == game::Role::kPursuer ? pursuers_learn : evaders_learn; };
  const auto n = std::count_if(entries_.begin(), entries_.end(), open);
  if (n == 0) return -1;
  // Two uniform draws: one for the share, one for the entry among the open ones.
  Rng rng(seed);
  if (unit_uniform(rng) >= training_.pool_share) return -1;
  auto k = static_cast<std::ptrdiff_t>(unit_uniform(rng) * static_cast<double>(n));
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    if (open(entries_[i]) && k-- == 0) return static_cast<int>(i);
  }
  return -1;  // unreachable: k < n
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
  const game::TrainingConfig& training = sim.config().training;
  const double share_random = training.random_starts;
  const int pursuer_episodes = learning_episodes(training.pursuer_learning, episodes);
  const int evader_episodes = learning_episodes(training.evader_learning, episodes);
  std::vector<Resting> resting;
  resting.reserve(std::size_t(lineup.size()));
  for (int i = 0; i < lineup.size(); ++i) resting.emplace_back(lineup[i]);
  world::Scenario random;
  playing.reserve(std::size_t(lineup.size()));
  for (int e = 0; e < episodes; ++e) {
    throw_if_stopped(stop);
    const world::Scenario* scenario = &scenarios[std::size_t(e) % scenarios.size()];
    if (share_random > 0.0) {
      Rng draw(stream(TrialStream::kTrainingStart, std::size_t(e)));
      if (unit_uniform(draw) < share_random) {
        random = game::random_start(sim, *scenario, draw());
        scenario = &random;
      }
    }
    const int p = static_cast<int>(scenario->pursuers.size()), q = static_cast<int>(scenario->evaders.size());
    assert(p <= pursuers && q <= evaders);
    const bool pursuers_learn = e < pursuer_episodes, evaders_learn = e < evader_episodes;
    const int k = entries.empty() ? -1
                                  : pool->choose(stream(TrialStream::kTrainingOpponent, std::size_t(e)), pursuers_learn,
                                                 evaders_learn);
    playing.clear();
    const game::Sim* played = &sim;
    if (k < 0) {
      for (int i = 0; i < p; ++i) playing.push_back(pursuers_learn ? &lineup[i] : &resting[std::size_t(i)]);
      for (int j = 0; j < q; ++j) playing.push_back(evaders_learn ? &lineup[pursuers + j] : &resting[std::size_t(pursuers + j)]);
    } else {
      const OpponentPool::Entry& entry = entries[std::size_t(k)];
      played = &entry.sim;
      const bool trains_pursuers = entry.learner == game::Role::kPursuer;
      auto& opponent = classic[std::size_t(k)];
      if (!opponent) {
        opponent = std::make_unique<game::Lineup>();
        game::add_configured(*opponent, entry.sim.config(), trains_pursuers ? game::Role::kEvader : game::Role::kPursuer,
                             trains_pursuers ? evaders : pursuers, stream(TrialStream::kPoolOpponents, std::size_t(k)));
      }
      for (int i = 0; i < p; ++i) playing.push_back(trains_pursuers ? &lineup[i] : &(*opponent)[i]);
      for (int j = 0; j < q; ++j) playing.push_back(trains_pursuers ? &(*opponent)[j] : &lineup[pursuers + j]);
    }
    results.push_back(game::play(*played, state, *scenario, playing, /*learning=*/true,
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
