// Training procedures (experiment/training.hpp): the opponent pool's entries, its episode draw, and trials
// that mix pool episodes into co-learning.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/hash.hpp"
#include "core/random.hpp"
#include "core/validation.hpp"
#include "experiment/training.hpp"
#include "experiment/trial.hpp"
#include "test_arena.hpp"

namespace peg3d::experiment {
namespace {

using game::PolicyKind;
using game::Role;

std::shared_ptr<const world::Arena> arena() {
  static const auto a = testing::make_arena({20, 20, 10}, {}, {testing::scenario("S1", {2, 2, 5}, {14, 14, 5})});
  return a;
}

game::GameConfig pool_config(double share = 0.5) {
  game::GameConfig c = game::preset("peg3d");
  c.time_limit = 10.0;
  c.training.procedure = game::TrainingProcedure::kOpponentPool;
  c.training.pool_share = share;
  return c;
}

std::uint64_t tables_hash(const game::RoleModels& models) {
  Fnv1a h;
  for (const auto& m : models.models) {
    for (int c = 0; c < m->channels(); ++c) {
      h.add_span(m->tables(c).actor_table());
      h.add_span(m->tables(c).critic_table());
    }
  }
  return h.value();
}

TEST(OpponentPool, CoLearningHasNoOpponents) {
  EXPECT_TRUE(OpponentPool(arena(), game::preset("peg3d")).empty());
}

TEST(OpponentPool, HoldsTheChosenClassicOpponentsOfEveryLearningRole) {
  game::GameConfig c = pool_config();
  c.training.pool_pn = false;
  c.training.pool_random = false;
  const OpponentPool pool(arena(), c);
  ASSERT_EQ(pool.entries().size(), 4u);
  const std::pair<Role, PolicyKind> expected[] = {{Role::kPursuer, PolicyKind::kFlee},
                                                  {Role::kPursuer, PolicyKind::kFleeApollonius},
                                                  {Role::kEvader, PolicyKind::kPurePursuit},
                                                  {Role::kEvader, PolicyKind::kApollonius}};
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& e = pool.entries()[k];
    EXPECT_EQ(e.learner, expected[k].first);
    EXPECT_EQ(e.opponent, expected[k].second);
    // The entry's Sim: the learner's side as configured, every agent of the other side scripted.
    const Role other = e.learner == Role::kPursuer ? Role::kEvader : Role::kPursuer;
    EXPECT_EQ(e.sim.config().agent(other).policy, e.opponent);
    EXPECT_FALSE(e.sim.config().agent(other).motion_space);
    EXPECT_EQ(e.sim.config().agent(e.learner), c.agent(e.learner));
  }
}

TEST(OpponentPool, OnlyARoleThatLearnsGetsOpponents) {
  game::GameConfig c = pool_config();
  c.evader = game::scripted_agent(c.evader, PolicyKind::kFlee);
  const OpponentPool pool(arena(), c);
  ASSERT_EQ(pool.entries().size(), 3u);
  for (const auto& e : pool.entries()) EXPECT_EQ(e.learner, Role::kPursuer);
}

TEST(OpponentPool, DrawsPoolEpisodesAtTheConfiguredShareAndEntriesUniformly) {
  for (const double share : {0.0, 0.3, 1.0}) {
    const OpponentPool pool(arena(), pool_config(share));
    const int n = 20000;
    std::vector<int> per_entry(pool.entries().size(), 0);
    int pooled = 0;
    for (int e = 0; e < n; ++e) {
      const int k = pool.choose(derive_seed(99, {std::uint64_t(e)}));
      ASSERT_GE(k, -1);
      ASSERT_LT(k, static_cast<int>(per_entry.size()));
      if (k >= 0) ++pooled, ++per_entry[std::size_t(k)];
    }
    // Binomial: 5 standard deviations (exact at the ends).
    EXPECT_NEAR(pooled, share * n, 5.0 * std::sqrt(n * share * (1 - share)) + 1e-9) << share;
    for (const int c : per_entry) {
      const double p = 1.0 / static_cast<double>(per_entry.size());
      EXPECT_NEAR(c, pooled * p, 5.0 * std::sqrt(pooled * p * (1 - p)) + 1e-9) << share;
    }
  }
}

TEST(OpponentPool, LeavesOutTheEntriesOfARoleThatNoLongerLearns) {
  const OpponentPool pool(arena(), pool_config(1.0));
  int evader_entries = 0;
  for (int e = 0; e < 3000; ++e) {
    const std::uint64_t seed = derive_seed(3, {std::uint64_t(e)});
    const int k = pool.choose(seed, /*pursuers_learn=*/false, /*evaders_learn=*/true);
    ASSERT_GE(k, 0);
    EXPECT_EQ(pool.entries()[std::size_t(k)].learner, Role::kEvader);
    evader_entries += k;
    EXPECT_EQ(pool.choose(seed, true, true), pool.choose(seed));
    EXPECT_EQ(pool.choose(seed, false, false), -1);
  }
  // Uniform over the three evader entries (3, 4, 5): mean 4.
  EXPECT_NEAR(evader_entries / 3000.0, 4.0, 0.1);
}

TEST(Training, ARoleStopsLearningAfterItsShareOfTheEpisodes) {
  // The pursuers learn in the first 3 of 6 episodes: their tables end as after 3 episodes, while the evaders'
  // go on changing, and no later episode draws a pool entry for the pursuers.
  game::GameConfig c = pool_config(0.5);
  c.training.pursuer_learning = 0.5;
  const game::Sim sim(arena(), c);
  const OpponentPool pool(arena(), c);
  const auto& s = arena()->map().scenarios[0];
  const TrialResult six = run_trial(sim, {&s, 13, 6, false, {}, &pool});
  game::GameConfig all = c;
  all.training.pursuer_learning = 1.0;
  const OpponentPool pool_all(arena(), all);
  const TrialResult three = run_trial(game::Sim(arena(), all), {&s, 13, 3, false, {}, &pool_all});
  EXPECT_EQ(tables_hash(six.pursuer_models), tables_hash(three.pursuer_models));
  EXPECT_NE(tables_hash(six.evader_models), tables_hash(three.evader_models));
  for (std::size_t e = 3; e < 6; ++e) {
    const int k = six.training.opponents[e];
    if (k >= 0) {
      EXPECT_EQ(pool.entries()[std::size_t(k)].learner, Role::kEvader) << e;
    }
  }
  // The first three episodes are the same either way.
  for (std::size_t e = 0; e < 3; ++e) EXPECT_EQ(six.training.episodes[e].steps, three.training.episodes[e].steps);
}

TEST(Training, RandomStartsChangeWhereEpisodesStartAndStayAFunctionOfTheSeed) {
  game::GameConfig c = pool_config(0.0);
  const game::Sim fixed(arena(), c);
  c.training.random_starts = 1.0;
  const game::Sim random(arena(), c);
  const OpponentPool pool(arena(), c);
  const auto& s = arena()->map().scenarios[0];
  const TrialResult a = run_trial(fixed, {&s, 5, 6, false, {}, &pool});
  const TrialResult b = run_trial(random, {&s, 5, 6, false, {}, &pool});
  const TrialResult b2 = run_trial(random, {&s, 5, 6, false, {}, &pool});
  int moved = 0;
  for (std::size_t e = 0; e < 6; ++e) {
    moved += a.training.episodes[e].pursuer_return != b.training.episodes[e].pursuer_return;
    EXPECT_EQ(b.training.episodes[e].pursuer_return, b2.training.episodes[e].pursuer_return);
  }
  EXPECT_GT(moved, 0);
  EXPECT_EQ(tables_hash(b.pursuer_models), tables_hash(b2.pursuer_models));
}

TEST(Training, ATrialWithAnOpponentPoolNeedsThePool) {
  const game::Sim sim(arena(), pool_config());
  EXPECT_THROW(run_trial(sim, {&arena()->map().scenarios[0], 7, 2, false, {}, nullptr}), std::logic_error);
}

TEST(Training, AZeroShareTrainsExactlyAsCoLearning) {
  game::GameConfig colearning = game::preset("peg3d");
  colearning.time_limit = 10.0;
  const game::GameConfig pooled = pool_config(0.0);
  const game::Sim a(arena(), colearning), b(arena(), pooled);
  const OpponentPool pool(arena(), pooled);
  const auto& s = arena()->map().scenarios[0];
  const TrialResult ra = run_trial(a, {&s, 7, 12, false, {}, nullptr});
  const TrialResult rb = run_trial(b, {&s, 7, 12, false, {}, &pool});
  ASSERT_EQ(ra.training.episodes.size(), rb.training.episodes.size());
  for (std::size_t e = 0; e < ra.training.episodes.size(); ++e) {
    EXPECT_EQ(ra.training.episodes[e].steps, rb.training.episodes[e].steps);
    EXPECT_EQ(ra.training.episodes[e].pursuer_return, rb.training.episodes[e].pursuer_return);
    EXPECT_EQ(rb.training.opponents[e], -1);
  }
  EXPECT_EQ(tables_hash(ra.pursuer_models), tables_hash(rb.pursuer_models));
  EXPECT_EQ(tables_hash(ra.evader_models), tables_hash(rb.evader_models));
}

TEST(Training, APoolEpisodeTeachesOnlyTheLearningRole) {
  // Share 1 with one evader in the pool and none for the pursuers' opponents: every episode the FACL
  // pursuer learns against flee, and the FACL evader never plays, so its tables stay as they started.
  game::GameConfig c = pool_config(1.0);
  c.training.pool_flee_apollonius = c.training.pool_random = false;
  c.training.pool_pure_pursuit = c.training.pool_pn = c.training.pool_apollonius = false;
  const game::Sim sim(arena(), c);
  const OpponentPool pool(arena(), c);
  ASSERT_EQ(pool.entries().size(), 1u);
  const auto& s = arena()->map().scenarios[0];
  const TrialResult r = run_trial(sim, {&s, 7, 6, false, {}, &pool});
  for (const int k : r.training.opponents) EXPECT_EQ(k, 0);

  game::GameConfig untrained = c;
  untrained.training.procedure = game::TrainingProcedure::kCoLearning;
  const TrialResult fresh = run_trial(game::Sim(arena(), untrained), {&s, 7, 0, false, {}, nullptr});
  EXPECT_EQ(tables_hash(r.evader_models), tables_hash(fresh.evader_models));
  EXPECT_NE(tables_hash(r.pursuer_models), tables_hash(fresh.pursuer_models));
}

TEST(Training, APooledTrialIsAFunctionOfItsSeed) {
  const game::GameConfig c = pool_config(0.5);
  const game::Sim sim(arena(), c);
  const OpponentPool pool(arena(), c);
  const auto& s = arena()->map().scenarios[0];
  const TrialResult a = run_trial(sim, {&s, 11, 16, false, {}, &pool});
  const TrialResult b = run_trial(sim, {&s, 11, 16, false, {}, &pool});
  EXPECT_EQ(a.training.opponents, b.training.opponents);
  EXPECT_EQ(tables_hash(a.pursuer_models), tables_hash(b.pursuer_models));
  EXPECT_EQ(tables_hash(a.evader_models), tables_hash(b.evader_models));
  int pooled = 0;
  for (const int k : a.training.opponents) pooled += k >= 0;
  EXPECT_GT(pooled, 0);
  EXPECT_LT(pooled, 16);
}

TEST(TrainingConfig, AnOpponentPoolWithoutOpponentsIsRejected) {
  game::GameConfig c = pool_config();
  c.training.pool_pure_pursuit = c.training.pool_pn = c.training.pool_apollonius = false;
  c.training.pool_flee = c.training.pool_flee_apollonius = c.training.pool_random = false;
  try {
    c.validate();
    FAIL() << "accepted an empty pool";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.parameter(), "training.procedure");
  }
  c.training.pool_share = 1.5;
  c.training.pool_flee = true;
  try {
    c.validate();
    FAIL() << "accepted pool_share 1.5";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.parameter(), "training.pool_share");
  }
}

}  // namespace
}  // namespace peg3d::experiment
