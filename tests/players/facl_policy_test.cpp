#include "players/facl_policy.hpp"

#include <algorithm>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "core/random.hpp"
#include "game/episode.hpp"
#include "players/policy_io.hpp"
#include "game/test_arena.hpp"

namespace peg3d::players {
namespace {

using namespace peg3d::game;

AgentView random_percept_view(Rng& rng) {
  std::uniform_real_distribution<double> d(0.0, 40.0), a(-kPi, kPi), z(0.0, kPi);
  AgentView v;
  v.percept.target_distance = d(rng);
  v.percept.target = {a(rng), a(rng)};
  v.percept.obstacle = {d(rng) / 8, Vec3::Zero(), true};
  v.percept.to_obstacle = {a(rng), a(rng)};
  return v;
}

// Learning on random transitions gives the tables distinct values.
void train_randomly(FaclPolicy& p, Rng& rng, int steps) {
  p.begin_episode({}, true);
  for (int i = 0; i < steps; ++i) {
    p.act(random_percept_view(rng));
    p.learn(std::uniform_real_distribution<double>(-5, 5)(rng), random_percept_view(rng), i % 50 == 49);
  }
}

TEST(FaclPolicy, TheOpponentsHeadingIsOneMoreInputOfEachChannel) {
  AgentConfig c = agent_preset("peg3d", Role::kEvader);  // per-angle: {0,1,3,4} and {0,2,3,5}
  c.observation.opponent_heading = true;
  const FaclModel per_angle(c, Role::kEvader);
  EXPECT_EQ(per_angle.features(0), (std::vector<int>{0, 1, 3, 4, 6}));
  EXPECT_EQ(per_angle.features(1), (std::vector<int>{0, 2, 3, 5, 7}));
  EXPECT_EQ(per_angle.tables(0).rules().rules(), facl_rules(c));
  EXPECT_EQ(facl_rules(c), 5 * 5 * 5 * 5 * 5);
  c.structure = FaclStructure::kJoint;
  EXPECT_EQ(FaclModel(c, Role::kEvader).features(0), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  c.observation.angles = AngleInputs::kAzimuth;
  EXPECT_EQ(FaclModel(c, Role::kEvader).features(0), (std::vector<int>{0, 1, 3, 4, 6}));
  // The features carry the percept's opponent heading.
  AgentView q;
  q.percept.opponent_heading = {0.25, -0.5};
  EXPECT_EQ(features_of(q)[6], 0.25);
  EXPECT_EQ(features_of(q)[7], -0.5);
}

TEST(FaclPolicy, TheSightIsTwoMoreInputsOfEachChannel) {
  AgentConfig c = agent_preset("peg3d", Role::kEvader);  // per-angle: {0,1,3,4} and {0,2,3,5}
  c.observation.sight_inputs = true;
  c.observation.sight_age_range = 6.0;
  const FaclModel per_angle(c, Role::kEvader);
  EXPECT_EQ(per_angle.features(0), (std::vector<int>{0, 1, 3, 4, 8, 9}));
  EXPECT_EQ(per_angle.features(1), (std::vector<int>{0, 2, 3, 5, 8, 9}));
  // Visibility has two sets, the age `sets`.
  EXPECT_EQ(facl_rules(c), 5 * 5 * 5 * 5 * 2 * 5);
  EXPECT_EQ(per_angle.tables(0).rules().rules(), facl_rules(c));
  EXPECT_EQ(per_angle.tables(0).rules().input(4).sets(), 2);
  EXPECT_EQ(per_angle.tables(0).rules().input(5).sets(), 5);
  EXPECT_EQ(per_angle.tables(0).rules().input(5).hi(), 6.0);
  c.structure = FaclStructure::kJoint;
  EXPECT_EQ(FaclModel(c, Role::kEvader).features(0), (std::vector<int>{0, 1, 2, 3, 4, 5, 8, 9}));
  // The features carry the view's sight: in sight now (1 or 0), and the sighting's age.
  AgentView seen, lost;
  lost.other_visible = false;
  lost.other_age = 2.5;
  EXPECT_EQ(features_of(seen)[8], 1.0);
  EXPECT_EQ(features_of(seen)[9], 0.0);
  EXPECT_EQ(features_of(lost)[8], 0.0);
  EXPECT_EQ(features_of(lost)[9], 2.5);
  // In sight and lost fire disjoint rules (those of strength > 0, which alone learn): what the agent learns while
  // it sees the opponent is its own.
  const FaclModel joint(c, Role::kEvader);
  fuzzy::FiredRules a, b;
  joint.fire(0, features_of(seen), a);
  joint.fire(0, features_of(lost), b);
  int strong = 0;
  for (int i = 0; i < a.count; ++i) {
    for (int j = 0; j < b.count; ++j) {
      if (a.strength[std::size_t(i)] > 0 && b.strength[std::size_t(j)] > 0) {
        ++strong;
        EXPECT_NE(a.rule[std::size_t(i)], b.rule[std::size_t(j)]);
      }
    }
  }
  EXPECT_GT(strong, 0);
}

TEST(FaclPolicy, SavedAndLoadedPoliciesActIdentically) {
  for (const char* name : {"peg3d", "paper"}) {
    const AgentConfig c = agent_preset(name, Role::kPursuer);
    FaclPolicy trained(c, Role::kPursuer, 5);
    Rng rng(1);
    train_randomly(trained, rng, 2000);
    const nlohmann::json doc = policy_to_json(trained.model());
    FaclPolicy loaded(std::shared_ptr<const FaclModel>(policy_from_json(nlohmann::json::parse(doc.dump()))));  // through text, as on disk
    trained.begin_episode({}, false);
    loaded.begin_episode({}, false);
    for (int i = 0; i < 1000; ++i) {
      const AgentView v = random_percept_view(rng);
      const Steering a = trained.act(v), b = loaded.act(v);
      ASSERT_EQ(a.d_alpha, b.d_alpha) << name;
      ASSERT_EQ(a.d_theta, b.d_theta) << name;
    }
  }
}

TEST(FaclPolicy, ActDependsOnlyOnItsViewAndTheTables) {
  // Two copies of one trained model and two policies with the same exploration seed. One acts right after
  // learn() (which fired the successor view), the other after a fresh begin_episode() (nothing fired): for
  // the view learn() saw and for any other view, both act the same.
  FaclPolicy trained(agent_preset("peg3d", Role::kEvader), Role::kEvader, 3);
  Rng rng(2);
  train_randomly(trained, rng, 500);
  const nlohmann::json doc = policy_to_json(trained.model());
  FaclPolicy a(policy_from_json(doc), 9), b(policy_from_json(doc), 9);
  a.begin_episode({}, true);
  b.begin_episode({}, true);
  for (int i = 0; i < 200; ++i) {
    const AgentView now = random_percept_view(rng), seen = random_percept_view(rng), other = random_percept_view(rng);
    const Steering ua = a.act(now), ub = b.act(now);
    ASSERT_EQ(ua.d_alpha, ub.d_alpha);
    a.learn(0.5, seen, false);
    b.learn(0.5, seen, false);
    b.begin_episode({}, true);  // forgets what learn() fired; the exploration stream goes on
    const AgentView& v = i % 2 == 0 ? seen : other;
    const Steering va = a.act(v), vb = b.act(v);
    ASSERT_EQ(va.d_alpha, vb.d_alpha) << i;
    ASSERT_EQ(va.d_theta, vb.d_theta) << i;
    const AgentView end = random_percept_view(rng);
    a.learn(-0.5, end, true);
    b.learn(-0.5, end, true);
  }
}


TEST(FaclPolicy, ATargetLineOffsetAddsTheTurnOntoTheLineAndLearnsTheSame) {
  // Two policies, one per action kind, with the same exploration seed and the same transitions: the tables
  // they learn are equal (the base turn cancels in the TD update), and each act of the offset policy is the
  // other's plus the percept's target errors. A fresh offset actor therefore flies pure pursuit.
  AgentConfig c = agent_preset("robust", Role::kPursuer);
  c.action = FaclAction::kHeadingChange;
  AgentConfig o = c;
  o.action = FaclAction::kTargetLineOffset;
  FaclPolicy plain(c, Role::kPursuer, 4), offset(o, Role::kPursuer, 4);
  Rng r1(5), r2(5);
  train_randomly(plain, r1, 500);
  train_randomly(offset, r2, 500);
  for (int ch = 0; ch < plain.model().channels(); ++ch) {
    const auto a = plain.model().tables(ch).actor_table(), b = offset.model().tables(ch).actor_table();
    ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << ch;
  }
  plain.begin_episode({}, false);
  offset.begin_episode({}, false);
  const FaclModel fresh_model(o, Role::kPursuer);
  FaclPolicy fresh{std::shared_ptr<const FaclModel>(std::make_shared<FaclModel>(fresh_model))};
  fresh.begin_episode({}, false);
  for (int i = 0; i < 50; ++i) {
    const AgentView v = random_percept_view(r1);
    const Steering p = plain.act(v), q = offset.act(v), f = fresh.act(v);
    EXPECT_DOUBLE_EQ(q.d_alpha, p.d_alpha + v.percept.target.azimuth);
    EXPECT_DOUBLE_EQ(q.d_theta, p.d_theta + v.percept.target.elevation);
    EXPECT_EQ(f.d_alpha, v.percept.target.azimuth);
    EXPECT_EQ(f.d_theta, v.percept.target.elevation);
  }
}
TEST(FaclPolicy, TeammatesShareOneModelAndFrozenModelsCannotLearn) {
  auto model = std::make_shared<FaclModel>(agent_preset("peg3d", Role::kPursuer), Role::kPursuer);
  FaclPolicy a(model, 1), b(model, 2);
  Rng rng(3);
  const double before = model->tables(0).critic_table()[0];
  train_randomly(a, rng, 300);
  EXPECT_NE(std::vector<double>(model->tables(0).critic_table().begin(), model->tables(0).critic_table().end()),
            std::vector<double>(model->tables(0).critic_table().size(), before));
  // b acts on what a learned.
  b.begin_episode({}, false);
  FaclPolicy frozen{std::shared_ptr<const FaclModel>(model)};
  frozen.begin_episode({}, false);
  const AgentView v = random_percept_view(rng);
  EXPECT_EQ(b.act(v).d_alpha, frozen.act(v).d_alpha);
  EXPECT_THROW(frozen.begin_episode({}, true), std::logic_error);
}

TEST(FaclPolicy, RejectsDocumentsThatDoNotFit) {
  const FaclModel m(agent_preset("peg3d", Role::kEvader), Role::kEvader);
  const nlohmann::json doc = policy_to_json(m);
  EXPECT_EQ(doc["format"], "peg3d-policy");
  EXPECT_EQ(doc["channels"].size(), 2u);
  const auto expect_error = [](const nlohmann::json& d, const std::string& field, std::optional<Role> role = std::nullopt) {
    try {
      policy_from_json(d, "p.json", role);
      ADD_FAILURE() << "accepted; expected an error at " << field;
    } catch (const PolicyFormatError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("p.json: ", 0), 0u) << e.what();
    }
  };
  nlohmann::json d = doc;
  d["version"] = 99;
  expect_error(d, "version");
  d = doc;
  d["channels"][0]["actor"].erase(0);
  expect_error(d, "channels[0].actor");
  d = doc;
  d["channels"][1]["critic"][3] = "x";
  expect_error(d, "channels[1].critic[3]");
  expect_error(nlohmann::json{{"format", "other"}}, "format");
  d = doc;
  d["config"]["facl"]["actor_rate"] = -1.0;
  expect_error(d, "config.facl.actor_rate");
  d = doc;
  d["config"]["facl"].erase("discount");
  expect_error(d, "config.facl.discount");  // saved policies are complete
  d = doc;
  d["config"]["colour"] = "blue";
  expect_error(d, "config.colour");
  d = doc;
  d["config"]["policy"] = "flee";
  expect_error(d, "config.policy");
  d = doc;
  d["role"] = "referee";
  expect_error(d, "role");
  expect_error(doc, "role", Role::kPursuer);  // an evader's policy cannot play the pursuer
  EXPECT_NO_THROW(policy_from_json(doc, "p.json", Role::kEvader));
  d = doc;
  d["config"]["guard"].erase("faces");
  expect_error(d, "config.guard.faces");  // version 2 documents have it
  d = doc;
  d["config"]["guard"].erase("look_ahead");
  expect_error(d, "config.guard.look_ahead");  // version 3 documents have it
  d = doc;
  d["config"]["observation"].erase("opponent_heading");
  expect_error(d, "config.observation.opponent_heading");  // version 4 documents have it
  d = doc;
  d["config"].erase("action");
  expect_error(d, "config.action");  // version 5 documents have it
  d = doc;
  d["config"].erase("lidar");
  expect_error(d, "config.lidar");  // version 6 documents have it
  d = doc;
  d["config"]["map"].erase("insert_agents");
  expect_error(d, "config.map.insert_agents");  // version 7 documents have it
  d = doc;
  d["config"].erase("sight");
  expect_error(d, "config.sight");  // version 8 documents have it
  d = doc;
  d["config"].erase("camera");
  expect_error(d, "config.camera");  // version 9 documents have it
  d = doc;
  d["config"]["observation"].erase("sight_inputs");
  expect_error(d, "config.observation.sight_inputs");  // version 10 documents have it
}

TEST(FaclPolicy, ReadsOlderDocumentsAsTheyPlayed) {
  // Version 1 predates guard.faces, guard.look_ahead, observation.opponent_heading, action and lidar, version 2
  // the look ahead, version 3 the opponent's heading, version 4 the action, version 5 the lidar, version 6
  // map.insert_agents, version 7 sight, version 8 the camera, version 9 the sight inputs; their agents played without
  // them (actions as heading changes, no lidar, agents in maps, full information, no camera, no sight inputs).
  AgentConfig offset = agent_preset("peg3d", Role::kEvader);
  offset.action = FaclAction::kTargetLineOffset;
  offset.sensors.lidar.azimuth_rays = 8;
  offset.sensors.sight.enabled = true;
  nlohmann::json saved = policy_to_json(FaclModel(offset, Role::kEvader));
  EXPECT_EQ(saved["version"], 10);
  EXPECT_TRUE(policy_from_json(saved, "p.json", Role::kEvader)->config().sensors.sight.enabled);
  EXPECT_EQ(policy_from_json(saved, "p.json", Role::kEvader)->config().action, FaclAction::kTargetLineOffset);
  EXPECT_EQ(policy_from_json(saved, "p.json", Role::kEvader)->config().sensors.lidar, offset.sensors.lidar);
  EXPECT_FALSE(policy_from_json(saved, "p.json", Role::kEvader)->config().map.insert_agents);
  const FaclModel m(agent_preset("peg3d", Role::kEvader), Role::kEvader);
  nlohmann::json doc = policy_to_json(m);
  // Version 9 agents had no sight inputs.
  doc["version"] = 9;
  doc["config"]["observation"].erase("sight_inputs");
  doc["config"]["observation"].erase("sight_age_range");
  EXPECT_EQ(policy_from_json(doc, "p.json", Role::kEvader)->config().observation, m.config().observation);
  // Version 8 agents had no camera.
  doc["version"] = 8;
  doc["config"].erase("camera");
  EXPECT_EQ(policy_from_json(doc, "p.json", Role::kEvader)->config().sensors.camera, sense::DepthCameraConfig{});
  // Version 7 agents had full information.
  doc["version"] = 7;
  doc["config"].erase("sight");
  EXPECT_EQ(policy_from_json(doc, "p.json", Role::kEvader)->config().sensors.sight, sense::SightConfig{});
  // Version 6 maps held the agents' echoes.
  doc["version"] = 6;
  doc["config"]["map"].erase("insert_agents");
  EXPECT_TRUE(policy_from_json(doc, "p.json", Role::kEvader)->config().map.insert_agents);
  doc["version"] = 5;
  doc["config"].erase("lidar");
  doc["config"].erase("map");
  EXPECT_FALSE(policy_from_json(doc, "p.json", Role::kEvader)->config().sensors.lidar.enabled());
  doc["version"] = 4;
  doc["config"].erase("action");
  const auto four = policy_from_json(doc, "p.json", Role::kEvader);
  EXPECT_EQ(four->config().action, FaclAction::kHeadingChange);
  doc["version"] = 3;
  doc["config"]["observation"].erase("opponent_heading");
  const auto three = policy_from_json(doc, "p.json", Role::kEvader);
  EXPECT_FALSE(three->config().observation.opponent_heading);
  EXPECT_EQ(three->config().guard.look_ahead, m.config().guard.look_ahead);
  doc["version"] = 2;
  doc["config"]["guard"].erase("look_ahead");
  const auto two = policy_from_json(doc, "p.json", Role::kEvader);
  EXPECT_EQ(two->config().guard.look_ahead, 0.0);
  EXPECT_TRUE(two->config().guard.faces);
  doc["version"] = 1;
  doc["config"]["guard"].erase("faces");
  const auto one = policy_from_json(doc, "p.json", Role::kEvader);
  EXPECT_FALSE(one->config().guard.faces);
  EXPECT_EQ(one->config().guard.look_ahead, 0.0);
  AgentConfig as_played = m.config();
  as_played.guard.faces = false;
  as_played.guard.look_ahead = 0.0;
  EXPECT_EQ(one->config(), as_played);
  doc["version"] = 0;
  EXPECT_THROW(policy_from_json(doc, "p.json", Role::kEvader), PolicyFormatError);
}

TEST(FaclPolicy, ShortTrainingCapturesMoreOftenThanBefore) {
  // A 20 x 20 x 10 m room; the pursuer starts facing away from the evader (+x while the evader is behind
  // it), without the Apollonius motion space, so only learning can turn it round. The evader flees.
  std::vector<world::Scenario> starts;
  for (const auto& [p, e] : {std::pair{Vec3(12, 10, 5), Vec3(4, 10, 5)}, std::pair{Vec3(12, 6, 4), Vec3(5, 14, 6)},
                             std::pair{Vec3(14, 14, 5), Vec3(6, 5, 5)}}) {
    starts.push_back(testing::scenario("s", p, e));
  }
  const auto arena = testing::make_arena({20, 20, 10}, {}, {});
  GameConfig c = preset("peg3d");
  c.initial_heading = InitialHeading::kPlusX;
  c.pursuer.motion_space = false;
  c.evader.policy = "flee";
  c.time_limit = 40.0;
  const Sim sim(arena, c);
  SimState state(sim);
  int before = 0, after = 0;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    for (std::uint64_t seed = 0; seed < 4; ++seed) {
      Lineup l = testing::lineup_for(c, starts[k], derive_seed(seed, {k, 1}), derive_seed(seed, {k, 2}));
      before += play(sim, state, starts[k], l.policies(), false, 0).captured();
      for (std::uint64_t episode = 0; episode < 120; ++episode) {
        play(sim, state, starts[k], l.policies(), true, derive_seed(seed, {k, 3, episode}));
      }
      after += play(sim, state, starts[k], l.policies(), false, 0).captured();
    }
  }
  std::printf("captures before %d, after %d of 12\n", before, after);
  EXPECT_GT(after, before);
  EXPECT_GE(after, 9);  // of 12
}

}  // namespace
}  // namespace peg3d::players
