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
#include "game/random_start.hpp"
#include "sweep/progress_reporter.hpp"

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

namespace {

// One training's episodes: which policies play episode e, where it starts, and playing it. The lineup's own
// policies learn across episodes; a pool entry's classic opponents are built on first use.
class Trainer {
 public:
  Trainer(const TrainingContext& context, game::Lineup& lineup)
      : c_(context),
        lineup_(lineup),
        entries_(context.pool != nullptr ? context.pool->entries() : std::span<const OpponentPool::Entry>{}),
        classic_(entries_.size()),
        evaders_(lineup.size() - context.pursuers),
        pursuer_episodes_(learning_episodes(context.sim->config().training.pursuer_learning, context.episodes)),
        evader_episodes_(learning_episodes(context.sim->config().training.evader_learning, context.episodes)) {
    resting_.reserve(std::size_t(lineup.size()));
    for (int i = 0; i < lineup.size(); ++i) resting_.emplace_back(lineup[i]);
    playing_.reserve(std::size_t(lineup.size()));
  }

  /// Plays training episode e; returns its result and its pool entry (-1: co-learning).
  std::pair<game::EpisodeResult, int> play(int e, game::SimState& state) {
    const world::Scenario& scenario = start_of(e);
    const bool pursuers_learn = e < pursuer_episodes_, evaders_learn = e < evader_episodes_;
    const int k = entries_.empty() ? -1
                                   : c_.pool->choose(stream(TrialStream::kTrainingOpponent, std::size_t(e)),
                                                     pursuers_learn, evaders_learn);
    const game::Sim& played = k < 0 ? choose_co_learning(scenario, pursuers_learn, evaders_learn)
                                    : choose_pool_entry(scenario, k);
    return {game::play(played, state, scenario, playing_, /*learning=*/true,
                       stream(TrialStream::kTrainingEpisode, std::size_t(e))),
            k};
  }

 private:
  std::uint64_t stream(TrialStream s, std::size_t i) const {
    return derive_seed(c_.seed, {static_cast<std::uint64_t>(s), static_cast<std::uint64_t>(i)});
  }

  // The scenario episode e starts from: the next of the list, or a random start drawn from the episode's seed.
  const world::Scenario& start_of(int e) {
    const world::Scenario& listed = c_.scenarios[std::size_t(e) % c_.scenarios.size()];
    const double share_random = c_.sim->config().training.random_starts;
    if (share_random > 0.0) {
      Rng draw(stream(TrialStream::kTrainingStart, std::size_t(e)));
      if (unit_uniform(draw) < share_random) {
        random_ = game::random_start(*c_.sim, listed, draw());
        return random_;
      }
    }
    return listed;
  }

  // Co-learning: the lineup's own policies, each resting once its role's learning share is over.
  const game::Sim& choose_co_learning(const world::Scenario& s, bool pursuers_learn, bool evaders_learn) {
    const int p = static_cast<int>(s.pursuers.size()), q = static_cast<int>(s.evaders.size());
    assert(p <= c_.pursuers && q <= evaders_);
    playing_.clear();
    for (int i = 0; i < p; ++i) playing_.push_back(pursuers_learn ? &lineup_[i] : &resting_[std::size_t(i)]);
    for (int j = 0; j < q; ++j) {
      const int at = c_.pursuers + j;
      playing_.push_back(evaders_learn ? &lineup_[at] : &resting_[std::size_t(at)]);
    }
    return *c_.sim;
  }

  // A pool episode: the learning role's policies (the same objects, so learning carries on) beside the pool
  // entry's classic policies.
  const game::Sim& choose_pool_entry(const world::Scenario& s, int k) {
    const int p = static_cast<int>(s.pursuers.size()), q = static_cast<int>(s.evaders.size());
    assert(p <= c_.pursuers && q <= evaders_);
    const OpponentPool::Entry& entry = entries_[std::size_t(k)];
    const bool trains_pursuers = entry.learner == game::Role::kPursuer;
    auto& opponent = classic_[std::size_t(k)];
    if (!opponent) {
      opponent = std::make_unique<game::Lineup>();
      game::add_configured(*opponent, entry.sim.config(), trains_pursuers ? game::Role::kEvader : game::Role::kPursuer,
                           trains_pursuers ? evaders_ : c_.pursuers, stream(TrialStream::kPoolOpponents, std::size_t(k)));
    }
    playing_.clear();
    for (int i = 0; i < p; ++i) playing_.push_back(trains_pursuers ? &lineup_[i] : &(*opponent)[i]);
    for (int j = 0; j < q; ++j) playing_.push_back(trains_pursuers ? &(*opponent)[j] : &lineup_[c_.pursuers + j]);
    return entry.sim;
  }

  const TrainingContext& c_;
  game::Lineup& lineup_;
  std::span<const OpponentPool::Entry> entries_;
  std::vector<std::unique_ptr<game::Lineup>> classic_;  // per pool entry, built on first use
  std::vector<Resting> resting_;                         // per lineup policy: it, not learning
  std::vector<game::Policy*> playing_;                   // the current episode's policies, in agent order
  world::Scenario random_;                               // the current episode's random start
  int evaders_;
  int pursuer_episodes_, evader_episodes_;
};

}  // namespace

TrainingResult train_lineup(const TrainingContext& context, game::Lineup& lineup, game::SimState& state) {
  const game::Sim& sim = *context.sim;
  if (sim.config().training.procedure != game::TrainingProcedure::kCoLearning && context.pool == nullptr) {
    throw std::logic_error("train_lineup: the configuration trains with an opponent pool, but none was given");
  }
  TrainingResult r;
  r.episodes.reserve(static_cast<std::size_t>(context.episodes));
  r.opponents.reserve(static_cast<std::size_t>(context.episodes));
  Trainer trainer(context, lineup);
  for (int e = 0; e < context.episodes; ++e) {
    sweep::throw_if_stopped(context.stop);
    auto [result, opponent] = trainer.play(e, state);
    r.episodes.push_back(result);
    r.opponents.push_back(opponent);
    if (context.progress) context.progress->episode_done();
  }
  return r;
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
