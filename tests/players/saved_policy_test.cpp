// SavedPolicy (players/saved_policy.hpp): one reader for both kinds of policy file, each played as its own kind.
#include "players/saved_policy.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "core/random.hpp"
#include "game/observation.hpp"
#include "game/episode.hpp"
#include "players/policy_io.hpp"
#include "view_writer.hpp"
#include "game/sim.hpp"
#include "game/test_arena.hpp"
#include "players/mlp_policy.hpp"
#include "world/map/map_loader.hpp"

namespace peg3d::players {
namespace {

using namespace peg3d::game;

std::filesystem::path temp(const std::string& name) { return std::filesystem::path(::testing::TempDir()) / name; }

AgentView random_view(Rng& rng) {
  std::uniform_real_distribution<double> d(0.5, 40.0), a(-kPi, kPi);
  AgentView v;
  v.percept.target_distance = d(rng);
  v.percept.target = {a(rng), a(rng)};
  v.percept.obstacle = {d(rng) / 8, Vec3::Zero(), true};
  v.percept.to_obstacle = {a(rng), a(rng)};
  v.self.position = {d(rng) / 2, d(rng) / 2, d(rng) / 4};
  v.other.position = {d(rng) / 2, d(rng) / 2, d(rng) / 4};
  return v;
}

// A FACL pursuer with distinct table values (learning on random transitions), saved to `file`.
std::shared_ptr<const FaclModel> trained_facl(const std::filesystem::path& file) {
  FaclPolicy p(agent_preset("peg3d", Role::kPursuer), Role::kPursuer, 5);
  Rng rng(1);
  p.begin_episode({}, true);
  for (int i = 0; i < 2000; ++i) {
    p.act(random_view(rng));
    p.learn(std::uniform_real_distribution<double>(-5, 5)(rng), random_view(rng), i % 50 == 49);
  }
  save_policy(file, p.model());
  return p.shared_model();
}

// A 20 -> 2 MLP whose weights all differ, saved to `file`.
void write_mlp(const std::filesystem::path& file, const std::string& role) {
  nlohmann::json w = nlohmann::json::array();
  for (int j = 0; j < 2; ++j) {
    nlohmann::json row = nlohmann::json::array();
    for (int i = 0; i < kObservationBase; ++i) row.push_back(0.01 * (i + 1) * (j == 0 ? 1 : -1));
    w.push_back(row);
  }
  const nlohmann::json doc{{"format", "peg3d-mlp"}, {"version", 1}, {"role", role}, {"inputs", 20}, {"action_bound", 0.4},
                           {"input_mean", std::vector<double>(20, 0.5)}, {"input_std", std::vector<double>(20, 2.0)},
                           {"layers", {{{"weights", w}, {"bias", {0.1, -0.2}}}}}};
  std::ofstream(file) << doc.dump(1);
}

TEST(SavedPolicy, AFaclFilePlaysAsItsModelWithItsOwnConfiguration) {
  const auto file = temp("saved_facl.json");
  const auto model = trained_facl(file);
  const auto saved = load_saved_policy(file, Role::kPursuer);
  EXPECT_STREQ(saved->kind_name(), "facl");
  ASSERT_NE(saved->config(), nullptr);
  EXPECT_EQ(*saved->config(), model->config());
  FaclPolicy reference(model);
  const auto player = saved->make(0);
  reference.begin_episode({}, false);
  player->begin_episode({}, false);
  Rng rng(2);
  int turned = 0;
  for (int i = 0; i < 500; ++i) {
    const AgentView v = random_view(rng);
    const Steering a = reference.act(v), b = player->act(v);
    ASSERT_EQ(a.d_alpha, b.d_alpha);
    ASSERT_EQ(a.d_theta, b.d_theta);
    turned += a.d_alpha != 0.0;
  }
  EXPECT_GT(turned, 400);  // the comparison is of real actions, not of zeros
}

TEST(SavedPolicy, AnMlpFilePlaysAsTheMlpWithTheGamesConfiguration) {
  // (Its observation is the game's: tests/python/test_policy_feed.py plays one against the batch.)
  const auto file = temp("saved_mlp.json");
  write_mlp(file, "evader");
  const auto saved = load_saved_policy(file, Role::kEvader);
  EXPECT_STREQ(saved->kind_name(), "mlp");
  EXPECT_EQ(saved->config(), nullptr);
  MlpPolicy reference(load_mlp_policy(file, Role::kEvader), 0);
  const auto player = saved->make(0);
  Rng rng(3);
  for (int i = 0; i < 200; ++i) {
    const testing::WrittenView w(random_view(rng));
    const AgentView& v = w.view;
    const Steering a = reference.act(v), b = player->act(v);
    ASSERT_EQ(a.d_alpha, b.d_alpha);
    ASSERT_EQ(a.d_theta, b.d_theta);
    ASSERT_NE(a.d_alpha, 0.0);
  }
}

TEST(SavedPolicy, TheHashIsOfTheModelNotOfTheFilesLayout) {
  const auto compact = temp("hash_compact.json"), pretty = temp("hash_pretty.json"), other = temp("hash_other.json");
  write_mlp(compact, "pursuer");
  const nlohmann::json doc = read_policy_document(compact).doc;
  std::ofstream(pretty) << doc.dump(4) << "\n";
  nlohmann::json changed = doc;
  changed["layers"][0]["bias"][0] = 0.3;
  std::ofstream(other) << changed.dump();
  const auto a = load_saved_policy(compact, Role::kPursuer), b = load_saved_policy(pretty, Role::kPursuer),
             c = load_saved_policy(other, Role::kPursuer);
  EXPECT_EQ(a->content_hash, b->content_hash);
  EXPECT_NE(a->content_hash, c->content_hash);
  EXPECT_EQ(a->content_hash.rfind("fnv1a64:", 0), 0u);
}

TEST(SavedPolicy, AFileOfTheOtherRoleOrNoPolicyIsRefusedNamingIt) {
  const auto mlp = temp("role_mlp.json"), facl = temp("role_facl.json"), junk = temp("role_junk.json");
  write_mlp(mlp, "pursuer");
  trained_facl(facl);
  std::ofstream(junk) << "{\"format\": \"something-else\"}";
  for (const auto& file : {mlp, facl, junk}) {
    try {
      load_saved_policy(file, Role::kEvader);
      ADD_FAILURE() << file << " was accepted";
    } catch (const PolicyFormatError& e) {
      EXPECT_NE(std::string(e.what()).find(file.filename().string()), std::string::npos) << e.what();
    }
  }
}

TEST(SavedPolicy, AddSavedGivesEachAgentItsOwnPlayer) {
  const auto file = temp("lineup_mlp.json");
  write_mlp(file, "pursuer");
  Lineup lineup;
  add_saved(lineup, *load_saved_policy(file, Role::kPursuer), 3, 0);
  ASSERT_EQ(lineup.size(), 3);
  EXPECT_NE(&lineup[0], &lineup[1]);
  EXPECT_NE(&lineup[1], &lineup[2]);
}

// An MLP file whose weights are finite but huge (alternating +-1e308) loads, and its network then gives NaN
// (inf - inf in a sum): play() stops at the first such step with the step's CommandError, naming the file.
TEST(SavedPolicy, AnOverflowingNetworkIsStoppedAtItsFirstStepNamingItsFile) {
  const auto file = temp("overflowing_mlp.json");
  nlohmann::json w = nlohmann::json::array();
  for (int j = 0; j < 2; ++j) {
    nlohmann::json row = nlohmann::json::array();
    for (int i = 0; i < kObservationBase; ++i) row.push_back(i % 2 ? -1e308 : 1e308);
    w.push_back(row);
  }
  const nlohmann::json doc{{"format", "peg3d-mlp"}, {"version", 1}, {"role", "pursuer"}, {"inputs", 20},
                           {"action_bound", 0.4}, {"input_mean", std::vector<double>(20, 0.0)},
                           {"input_std", std::vector<double>(20, 0.01)}, {"layers", {{{"weights", w}, {"bias", {0.0, 0.0}}}}}};
  std::ofstream(file) << doc.dump();
  const auto saved = load_saved_policy(file, Role::kPursuer);
  const auto s = testing::scenario("chase", {5, 5, 5}, {20, 25, 12});
  GameConfig c = preset("peg3d");
  c.evader.policy = "flee";
  const Sim sim(testing::make_arena(Vec3(35, 35, 20), {}, {s}), c);
  Lineup lineup;
  add_saved(lineup, *saved, 1, 0);
  add_configured(lineup, c, Role::kEvader, 1, 3);
  SimState state(sim);
  try {
    play(sim, state, s, lineup.policies(), false, 3);
    ADD_FAILURE() << "the episode was played to its end";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.step(), 1);
    EXPECT_EQ(e.agent(), 0);
    EXPECT_EQ(e.file(), file);
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(file.string() + ": step 1: agent 0 (pursuer 0), played by this policy file: steering command (", 0), 0u) << what;
  }
  EXPECT_EQ(state.step, 0);
}

TEST(SavedPolicy, TheShippedTeamThatSeesItsTeammatesReadsThemOnOpenWall) {
  // tests/data/policies/mappo_open_team.json (docs/learning.md, "A MAPPO team that sees its teammates"): in OPEN's
  // settings each of the four pursuers fits, and the slots it reads hold its three teammates, nearest first.
  const auto file = std::filesystem::path(PEG3D_TEST_DATA_DIR) / "policies/mappo_open_team.json";
  const auto saved = load_saved_policy(file, Role::kPursuer);
  const auto model = load_mlp_policy(file, Role::kPursuer);
  GameConfig c = preset("peg3d");
  c.pursuer.sensors.sight.enabled = c.evader.sensors.sight.enabled = true;
  c.pursuer.sensors.sight.fov = 120.0;
  c.pursuer.sensors.sight.share = true;
  c.pursuer.speed = 1.0, c.evader.speed = 1.3, c.capture_distance = 0.3;
  const auto arena = world::Arena::build(world::load_map(std::filesystem::path(PEG3D_SOURCE_DIR) / "maps/open_wall.yaml"));
  const Sim sim(arena, c);
  SimState st(sim);
  reset(sim, st, arena->map().scenarios.front(), 1);
  ASSERT_EQ(st.agent_count(), 5);
  for (int rank = 0; rank < 4; ++rank) {
    saved->check_fits(sim, Role::kPursuer, rank);
    const ObservationTable table = bind_observation(sim, Role::kPursuer, rank, model->observation);
    ASSERT_EQ(table.size(), 46);
    std::vector<float> obs(std::size_t(table.size()));
    write_observation(sim, st, rank, table, obs);
    const Vec3 self = st.agents[std::size_t(rank)].kinematics.position;
    double last = 0.0;
    for (int m = 0; m < 3; ++m) {
      const std::string slot = "neighbour.teammate." + std::to_string(m);
      EXPECT_EQ(obs[std::size_t(table.find(slot + ".mask")->offset)], 1.0f) << slot;
      const int at = table.find(slot + ".offset")->offset;
      const Vec3 offset(obs[std::size_t(at)], obs[std::size_t(at + 1)], obs[std::size_t(at + 2)]);
      bool a_teammate = false;  // the offset is one of the other pursuers'
      for (int j = 0; j < 4; ++j) {
        a_teammate = a_teammate || (j != rank && (st.agents[std::size_t(j)].kinematics.position - self - offset).norm() < 1e-5);
      }
      EXPECT_TRUE(a_teammate) << slot;
      EXPECT_GE(offset.norm(), last - 1e-6) << slot;  // nearest first
      last = offset.norm();
    }
  }
  // Without limited sight the agents' observation lacks what the team reads: refused, naming the segment.
  GameConfig full = c;
  full.pursuer.sensors.sight.enabled = false;
  try {
    saved->check_fits(Sim(arena, full), Role::kPursuer, 0);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sight.visible"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace peg3d::players
