#include "game/facl_policy.hpp"

#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "core/random.hpp"
#include "game/episode.hpp"
#include "game/policy_io.hpp"
#include "test_arena.hpp"

namespace peg3d::game {
namespace {

AgentView random_view(Rng& rng) {
  std::uniform_real_distribution<double> d(0.0, 40.0), a(-kPi, kPi), z(0.0, kPi);
  AgentView v;
  v.percept.target_distance = d(rng);
  v.percept.target = {a(rng), a(rng)};
  v.percept.obstacle = {d(rng) / 8, Vec3::Zero(), true};
  v.percept.to_obstacle = {a(rng), a(rng)};
  return v;
}

TEST(FaclPolicy, SavedAndLoadedPoliciesActIdentically) {
  for (const char* name : {"peg3d", "paper"}) {
    const AgentConfig c = agent_preset(name, Role::kPursuer);
    FaclPolicy trained(c, Role::kPursuer, 5);
    // Give the tables distinct values through learning on random transitions.
    Rng rng(1);
    trained.begin_episode({}, true);
    for (int i = 0; i < 2000; ++i) {
      trained.act(random_view(rng));
      trained.learn(std::uniform_real_distribution<double>(-5, 5)(rng), random_view(rng), i % 50 == 49);
    }
    const nlohmann::json doc = policy_to_json(trained);
    const auto loaded = policy_from_json(nlohmann::json::parse(doc.dump()));  // through text, as on disk
    trained.begin_episode({}, false);
    loaded->begin_episode({}, false);
    for (int i = 0; i < 1000; ++i) {
      const AgentView v = random_view(rng);
      const Steering a = trained.act(v), b = loaded->act(v);
      ASSERT_EQ(a.d_alpha, b.d_alpha) << name;
      ASSERT_EQ(a.d_theta, b.d_theta) << name;
    }
  }
}

TEST(FaclPolicy, RejectsDocumentsThatDoNotFit) {
  const FaclPolicy p(agent_preset("peg3d", Role::kEvader), Role::kEvader, 1);
  nlohmann::json doc = policy_to_json(p);
  EXPECT_EQ(doc["format"], "peg3d-policy");
  EXPECT_EQ(doc["channels"].size(), 2u);
  nlohmann::json wrong_version = doc;
  wrong_version["version"] = 99;
  EXPECT_THROW(policy_from_json(wrong_version), PolicyFormatError);
  nlohmann::json short_table = doc;
  short_table["channels"][0]["actor"].erase(0);
  EXPECT_THROW(policy_from_json(short_table), PolicyFormatError);
  EXPECT_THROW(policy_from_json(nlohmann::json{{"format", "other"}}), PolicyFormatError);
  nlohmann::json bad_config = doc;
  bad_config["config"]["facl"]["actor_rate"] = -1.0;
  EXPECT_THROW(policy_from_json(bad_config), PolicyFormatError);
}

TEST(FaclPolicy, ShortTrainingCapturesMoreOftenThanBefore) {
  // A 20 x 20 x 10 m room; the pursuer starts facing away from the evader (+x while the evader is behind
  // it), without the Apollonius motion space, so only learning can turn it round. The evader flees.
  std::vector<world::Scenario> starts;
  for (const auto& [p, e] : {std::pair{Vec3(12, 10, 5), Vec3(4, 10, 5)}, std::pair{Vec3(12, 6, 4), Vec3(5, 14, 6)},
                             std::pair{Vec3(14, 14, 5), Vec3(6, 5, 5)}}) {
    starts.push_back(testing::scenario("s", p, e));
  }
  const auto arena = testing::make_arena({20, 20, 10}, {}, starts);
  GameConfig c = preset("peg3d");
  c.initial_heading = InitialHeading::kPlusX;
  c.pursuer.motion_space = false;
  c.evader.policy = "flee";
  c.time_limit = 40.0;
  int before = 0, after = 0;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    for (std::uint64_t seed = 0; seed < 4; ++seed) {
      Game game(arena, c);
      auto p = make_policy(c.pursuer, Role::kPursuer, derive_seed(seed, {k, 1}));
      auto e = make_policy(c.evader, Role::kEvader, derive_seed(seed, {k, 2}));
      before += game.play(starts[k], *p, *e, false, 0).captured();
      for (std::uint64_t episode = 0; episode < 120; ++episode) game.play(starts[k], *p, *e, true, derive_seed(seed, {k, 3, episode}));
      after += game.play(starts[k], *p, *e, false, 0).captured();
    }
  }
  std::printf("captures before %d, after %d of 12\n", before, after);
  EXPECT_GT(after, before);
  EXPECT_GE(after, 9);  // of 12
}

}  // namespace
}  // namespace peg3d::game
