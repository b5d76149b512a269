// Training procedures (experiment/training.hpp, experiment/opponent_pool.hpp): the opponent pool's entries, its
// episode draw, and trials that mix pool episodes into co-learning; the trial's configuration and presets
// (experiment/trial_config.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/hash.hpp"
#include "core/random.hpp"
#include "core/config_json.hpp"
#include "core/validation.hpp"
#include "experiment/training.hpp"
#include "experiment/trial.hpp"
#include "experiment/trial_config.hpp"
#include "support/facl_tables_hash.hpp"
#include "test_arena.hpp"

namespace peg3d::experiment {
namespace {

using game::Role;

std::shared_ptr<const world::Arena> training_arena() {
  static const auto a = testing::make_arena({20, 20, 10}, {}, {testing::scenario("S1", {2, 2, 5}, {14, 14, 5})});
  return a;
}

TrialConfig pool_config(double share = 0.5) {
  TrialConfig c = trial_preset("peg3d");
  c.game.time_limit = 10.0;
  c.training.procedure = TrainingProcedure::kOpponentPool;
  c.training.pool.share = share;
  return c;
}

OpponentPool pool_of(const TrialConfig& c) { return make_pool(training_arena(), c.game, c.training); }

// A trial of `episodes` episodes from the arena's start, seeded `seed`, trained as `c` says with `pool`.
TrialResult trial(const TrialConfig& c, std::uint64_t seed, int episodes, const OpponentPool* pool) {
  return run_trial(game::Sim(training_arena(), c.game), {.scenario = &training_arena()->map().scenarios[0],
                                                .seed = seed,
                                                .episodes = episodes,
                                                .training = c.training,
                                                .pool = pool});
}

using testing::tables_hash;

TEST(OpponentPool, CoLearningHasNoOpponents) { EXPECT_TRUE(pool_of(trial_preset("peg3d")).empty()); }

TEST(OpponentPool, HoldsTheChosenClassicOpponentsOfEveryLearningRole) {
  TrialConfig c = pool_config();
  c.training.pool.pursuers = {"pure-pursuit", "apollonius"};
  c.training.pool.evaders = {"flee", "flee-apollonius"};
  const OpponentPool pool = pool_of(c);
  ASSERT_EQ(pool.entries().size(), 4u);
  const std::pair<Role, std::string> expected[] = {{Role::kPursuer, "flee"},
                                                  {Role::kPursuer, "flee-apollonius"},
                                                  {Role::kEvader, "pure-pursuit"},
                                                  {Role::kEvader, "apollonius"}};
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& e = pool.entries()[k];
    EXPECT_EQ(e.learner, expected[k].first);
    EXPECT_EQ(e.opponent, expected[k].second);
    // The entry's Sim: the learner's side as configured, every agent of the other side scripted.
    const Role other = e.learner == Role::kPursuer ? Role::kEvader : Role::kPursuer;
    EXPECT_EQ(e.sim.config().agent(other).policy, e.opponent);
    EXPECT_FALSE(e.sim.config().agent(other).motion_space);
    EXPECT_EQ(e.sim.config().agent(e.learner), c.game.agent(e.learner));
  }
}

TEST(OpponentPool, OnlyARoleThatLearnsGetsOpponents) {
  TrialConfig c = pool_config();
  c.game.evader = game::scripted_agent(c.game.evader, "flee");
  const OpponentPool pool = pool_of(c);
  ASSERT_EQ(pool.entries().size(), 3u);
  for (const auto& e : pool.entries()) EXPECT_EQ(e.learner, Role::kPursuer);
}

TEST(OpponentPool, DrawsPoolEpisodesAtTheConfiguredShareAndEntriesUniformly) {
  for (const double share : {0.0, 0.3, 1.0}) {
    const OpponentPool pool = pool_of(pool_config(share));
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
  const OpponentPool pool = pool_of(pool_config(1.0));
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
  TrialConfig c = pool_config(0.5);
  c.training.pursuer_learning = 0.5;
  const OpponentPool pool = pool_of(c);
  const TrialResult six = trial(c, 13, 6, &pool);
  TrialConfig all = c;
  all.training.pursuer_learning = 1.0;
  const OpponentPool pool_all = pool_of(all);
  const TrialResult three = trial(all, 13, 3, &pool_all);
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
  const TrialConfig fixed = pool_config(0.0);
  TrialConfig random = fixed;
  random.training.random_starts = 1.0;
  const OpponentPool pool = pool_of(fixed);
  const TrialResult a = trial(fixed, 5, 6, &pool);
  const TrialResult b = trial(random, 5, 6, &pool);
  const TrialResult b2 = trial(random, 5, 6, &pool);
  int moved = 0;
  for (std::size_t e = 0; e < 6; ++e) {
    moved += a.training.episodes[e].pursuer_return != b.training.episodes[e].pursuer_return;
    EXPECT_EQ(b.training.episodes[e].pursuer_return, b2.training.episodes[e].pursuer_return);
  }
  EXPECT_GT(moved, 0);
  EXPECT_EQ(tables_hash(b.pursuer_models), tables_hash(b2.pursuer_models));
}

TEST(Training, ATrialWithAnOpponentPoolNeedsThePool) {
  EXPECT_THROW(trial(pool_config(), 7, 2, nullptr), std::logic_error);
}

TEST(Training, AZeroShareTrainsExactlyAsCoLearning) {
  TrialConfig colearning = trial_preset("peg3d");
  colearning.game.time_limit = 10.0;
  const TrialConfig pooled = pool_config(0.0);
  const OpponentPool pool = pool_of(pooled);
  const TrialResult ra = trial(colearning, 7, 12, nullptr);
  const TrialResult rb = trial(pooled, 7, 12, &pool);
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
  TrialConfig c = pool_config(1.0);
  c.training.pool.evaders = {"flee"};
  c.training.pool.pursuers = {};
  const OpponentPool pool = pool_of(c);
  ASSERT_EQ(pool.entries().size(), 1u);
  const TrialResult r = trial(c, 7, 6, &pool);
  for (const int k : r.training.opponents) EXPECT_EQ(k, 0);

  TrialConfig untrained = c;
  untrained.training.procedure = TrainingProcedure::kCoLearning;
  const TrialResult fresh = trial(untrained, 7, 0, nullptr);
  EXPECT_EQ(tables_hash(r.evader_models), tables_hash(fresh.evader_models));
  EXPECT_NE(tables_hash(r.pursuer_models), tables_hash(fresh.pursuer_models));
}

TEST(Training, APooledTrialIsAFunctionOfItsSeed) {
  const TrialConfig c = pool_config(0.5);
  const OpponentPool pool = pool_of(c);
  const TrialResult a = trial(c, 11, 16, &pool);
  const TrialResult b = trial(c, 11, 16, &pool);
  EXPECT_EQ(a.training.opponents, b.training.opponents);
  EXPECT_EQ(tables_hash(a.pursuer_models), tables_hash(b.pursuer_models));
  EXPECT_EQ(tables_hash(a.evader_models), tables_hash(b.evader_models));
  int pooled = 0;
  for (const int k : a.training.opponents) pooled += k >= 0;
  EXPECT_GT(pooled, 0);
  EXPECT_LT(pooled, 16);
}

TEST(TrainingConfig, AnOpponentPoolWithoutOpponentsIsRejected) {
  TrialConfig c = pool_config();
  c.training.pool.pursuers = {};
  c.training.pool.evaders = {};
  try {
    c.validate();
    FAIL() << "accepted an empty pool";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.parameter(), "training.procedure");
  }
  c.training.pool.share = 1.5;
  c.training.pool.evaders = {"flee"};
  try {
    c.validate();
    FAIL() << "accepted pool.share 1.5";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.parameter(), "training.pool.share");
  }
}

TEST(TrainingConfig, ThePoolNamesClassicPlayersOfTheRightRoleOnly) {
  // Each case: the pool's lists, and the field the refusal names.
  const std::vector<std::tuple<std::vector<std::string>, std::vector<std::string>, std::string>> bad{
      {{"pn", "flee"}, {"flee"}, "training.pool.pursuers.1"},     // an evader among the pursuers
      {{"pn"}, {"facl"}, "training.pool.evaders.0"},              // a learner is no classic opponent
      {{"pn"}, {"flee", "teleport"}, "training.pool.evaders.1"},  // no such player
      {{"Pn"}, {"flee"}, "training.pool.pursuers.0"},             // not a name
  };
  for (const auto& [pursuers, evaders, field] : bad) {
    TrialConfig c = pool_config();
    c.training.pool.pursuers = pursuers;
    c.training.pool.evaders = evaders;
    try {
      c.validate();
      ADD_FAILURE() << field << " accepted";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.parameter(), field) << e.what();
    }
  }
}

TEST(TrainingConfig, ThePoolsPlayersTravelThroughJsonAndSetAsCommaLists) {
  // --set takes a list of names as commas (or JSON); the JSON image lists them.
  const TrialConfig c = load_trial_config("peg3d", {"training.procedure=opponent-pool", "training.pool.evaders=flee,random",
                                                    "training.pool.pursuers=[\"pn\"]"});
  EXPECT_EQ(c.training.pool.evaders, (std::vector<std::string>{"flee", "random"}));
  EXPECT_EQ(c.training.pool.pursuers, std::vector<std::string>{"pn"});
  TrialConfig back = trial_preset("peg3d");
  config::from_json(config::to_json(c), back);
  EXPECT_EQ(back, c);
  EXPECT_EQ(load_trial_config("peg3d", {"training.pool.evaders="}).training.pool.evaders, std::vector<std::string>{});
}

TEST(TrialConfig, PresetsTrainAsDocumented) {
  // robust trains with the opponent pool (share 0.8, the baselines of each role), random starts and pursuers that
  // learn in the first half of the training only (docs/learning.md); the other presets co-learn.
  TrainingConfig robust;
  robust.procedure = TrainingProcedure::kOpponentPool;
  robust.pool.share = 0.8;
  robust.random_starts = 1.0;
  robust.pursuer_learning = 0.5;
  EXPECT_EQ(trial_preset("robust").training, robust);
  EXPECT_EQ(robust.pool.pursuers, (std::vector<std::string>{"pure-pursuit", "pn", "apollonius"}));
  EXPECT_EQ(robust.pool.evaders, (std::vector<std::string>{"flee", "flee-apollonius", "random"}));
  for (const char* name : game::kPresetNames) {
    EXPECT_EQ(trial_preset(name).game, game::preset(name)) << name;
    if (std::string(name) != "robust") {
      EXPECT_EQ(trial_preset(name).training, TrainingConfig{}) << name;
    }
  }
}

TEST(TrialConfig, ItsImageIsTheGamesFieldsWithTheTrainingBeside) {
  const TrialConfig c = trial_preset("robust");
  nlohmann::json game = config::to_json(c.game);
  game["training"] = config::to_json(c.training);
  EXPECT_EQ(config::to_json(c), game);
  EXPECT_EQ(config::table_field_count<TrainingConfig>(), static_cast<int>(config::member_count<TrainingConfig>()));
  EXPECT_EQ(config::table_field_count<OpponentPoolConfig>(), static_cast<int>(config::member_count<OpponentPoolConfig>()));
}

TEST(TrialConfig, APolicyThatIsNoPlayerOfItsRoleIsRefusedNamingTheField) {
  for (const auto& [set, field] : std::vector<std::pair<std::string, std::string>>{
           {"pursuer.policy=flee", "pursuer.policy"}, {"evader.policy=teleport", "evader.policy"}}) {
    try {
      load_trial_config("peg3d", {set});
      ADD_FAILURE() << set;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.parameter(), field) << e.what();
    }
  }
}

}  // namespace
}  // namespace peg3d::experiment
