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

// A learning policy whose role's training is over: it plays its policy greedily and learns nothing.
class Resting final : public game::Policy {
 public:
  explicit Resting(game::Policy& policy) : policy_(&policy) {}
  void begin_episode(const game::AgentView& view, bool) override { policy_->begin_episode(view, false); }
  Steering act(const game::AgentView& view) override { return policy_->act(view); }
  bool scripted() const override { return policy_->scripted(); }

 private:
  game::Policy* policy_;
};

}  // namespace

OpponentPool make_pool(const std::shared_ptr<const world::Arena>& arena, const game::GameConfig& config,
                       const TrainingConfig& training) {
  return OpponentPool(arena, config, training.pool, training.procedure == TrainingProcedure::kOpponentPool);
}

std::uint64_t stream_seed(std::uint64_t trial_seed, TrialStream s) {
  return derive_seed(trial_seed, {static_cast<std::uint64_t>(s)});
}

namespace {

// One training's episodes: which policies play episode e, where it starts, and playing it. The lineup's own
// policies learn across episodes; a pool entry's classic opponents are built on first use.
class Trainer {
 public:
  Trainer(const TrainingContext& context, players::Lineup& lineup)
      : c_(context),
        lineup_(lineup),
        entries_(context.pool != nullptr ? context.pool->entries() : std::span<const OpponentPool::Entry>{}),
        classic_(entries_.size()),
        evaders_(lineup.size() - context.pursuers),
        pursuer_episodes_(learning_episodes(context.training.pursuer_learning, context.episodes)),
        evader_episodes_(learning_episodes(context.training.evader_learning, context.episodes)) {
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
    const double share_random = c_.training.random_starts;
    if (share_random > 0.0) {
      Rng draw(stream(TrialStream::kTrainingStart, std::size_t(e)));
      if (unit_uniform(draw) < share_random) {
        random_ = game::random_start(*c_.sim, listed, draw(), c_.training.random_start_gap);
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
      opponent = std::make_unique<players::Lineup>();
      players::add_configured(*opponent, entry.sim.config(), trains_pursuers ? game::Role::kEvader : game::Role::kPursuer,
                           trains_pursuers ? evaders_ : c_.pursuers, stream(TrialStream::kPoolOpponents, std::size_t(k)));
    }
    playing_.clear();
    for (int i = 0; i < p; ++i) playing_.push_back(trains_pursuers ? &lineup_[i] : &(*opponent)[i]);
    for (int j = 0; j < q; ++j) playing_.push_back(trains_pursuers ? &(*opponent)[j] : &lineup_[c_.pursuers + j]);
    return entry.sim;
  }

  const TrainingContext& c_;
  players::Lineup& lineup_;
  std::span<const OpponentPool::Entry> entries_;
  std::vector<std::unique_ptr<players::Lineup>> classic_;  // per pool entry, built on first use
  std::vector<Resting> resting_;                         // per lineup policy: it, not learning
  std::vector<game::Policy*> playing_;                   // the current episode's policies, in agent order
  world::Scenario random_;                               // the current episode's random start
  int evaders_;
  int pursuer_episodes_, evader_episodes_;
};

}  // namespace

TrainingResult train_lineup(const TrainingContext& context, players::Lineup& lineup, game::SimState& state) {
  if (context.training.procedure != TrainingProcedure::kCoLearning && context.pool == nullptr) {
    throw std::logic_error("train_lineup: the training is by opponent pool, but none was given");
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

}  // namespace peg3d::experiment
