// SavedPolicy (players/saved_policy.hpp): one reader for both kinds of policy file, each played as its own kind.
#include "players/saved_policy.hpp"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "core/random.hpp"
#include "game/observation.hpp"
#include "game/episode.hpp"
#include "players/policy_io.hpp"
#include "players/registry.hpp"
#include "view_writer.hpp"
#include "game/sim.hpp"
#include "game/test_arena.hpp"
#include "players/mlp_policy.hpp"
#include "world/map/map_loader.hpp"

namespace peg3d::players {
namespace {

using namespace peg3d::game;

std::filesystem::path temp(const std::string& name) { return std::filesystem::path(::testing::TempDir()) / name; }

AgentView random_saved_view(Rng& rng) {
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
    p.act(random_saved_view(rng));
    p.learn(std::uniform_real_distribution<double>(-5, 5)(rng), random_saved_view(rng), i % 50 == 49);
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
  const auto player = saved->make(0, game::AgentConfig{}, Role::kPursuer, 0);
  reference.begin_episode({}, false);
  player->begin_episode({}, false);
  Rng rng(2);
  int turned = 0;
  for (int i = 0; i < 500; ++i) {
    const AgentView v = random_saved_view(rng);
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
  const auto player = saved->make(0, AgentConfig{}, Role::kEvader, 0);
  Rng rng(3);
  for (int i = 0; i < 200; ++i) {
    const testing::WrittenView w(random_saved_view(rng));
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
  add_saved(lineup, *load_saved_policy(file, Role::kPursuer), game::GameConfig{}, Role::kPursuer, 3, 0);
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
  add_saved(lineup, *saved, game::GameConfig{}, Role::kPursuer, 1, 0);
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

// A mixture file at `file`: role and members as given.
void write_mixture(const std::filesystem::path& file, const std::string& role, const nlohmann::json& members) {
  std::ofstream(file) << nlohmann::json{{"format", "peg3d-mixture"}, {"version", 1}, {"role", role}, {"members", members}}.dump(1);
}

TEST(SavedPolicy, AMixtureFileDrawsAMemberByWeightEachEpisodeTheSameForATeam) {
  // pure-pursuit 3, pn 1, an MLP file of weight 0 (read relative to the mixture's folder, never drawn). Two agents
  // of one team seed play the same member in each of 4000 episodes; pure-pursuit's share is 0.75 within 5 sd.
  const std::filesystem::path dir = temp("mixture_draws");
  std::filesystem::create_directories(dir);
  write_mlp(dir / "net.json", "pursuer");
  write_mixture(dir / "mix.json", "pursuer",
                {{{"policy", "pure-pursuit"}, {"weight", 3}}, {{"policy", "pn"}, {"weight", 1}}, {{"policy", "net.json"}, {"weight", 0}}});
  const auto saved = load_saved_policy(dir / "mix.json", Role::kPursuer);
  EXPECT_STREQ(saved->kind_name(), "mixture");
  ASSERT_EQ(saved->members.size(), 3u);
  EXPECT_EQ(saved->config(), nullptr);
  AgentConfig agent = agent_preset("peg3d", Role::kPursuer);
  agent.pn_gain = 4.5;  // the game's own gain: the member is made with the agent's configuration
  const auto a = saved->make(1, agent, Role::kPursuer, 77), b = saved->make(2, agent, Role::kPursuer, 77);
  AgentConfig pp = agent, pn = agent, net = agent;
  pp.policy = "pure-pursuit";
  pn.policy = "pn";
  const auto pure = make_player(pp, Role::kPursuer, 0), prop = make_player(pn, Role::kPursuer, 0);
  pn.pn_gain = 3.0;
  const auto default_gain = make_player(pn, Role::kPursuer, 0);
  Rng rng(9);
  const int n = 4000;
  int pursuit = 0, gain_differs = 0;
  int told = 0;  // episodes whose second step tells pure pursuit from pn (pn steers by the sight line's turn)
  for (int e = 0; e < n; ++e) {
    AgentView first = random_saved_view(rng);
    first.self_speed = 1.0, first.other_speed = 0.8;  // pn steers by the sight line's turn: relative motion
    first.self.heading = {std::uniform_real_distribution<double>(-kPi, kPi)(rng), 1.2};
    first.other.heading = {std::uniform_real_distribution<double>(-kPi, kPi)(rng), 1.9};
    AgentView second = first;
    second.other.position += Vec3(0.3, -0.2, 0.1);
    second.time = first.time + first.dt;
    const testing::WrittenView w1(first), w2(second);
    Steering sa, sb, sp, sn, sd;
    for (const testing::WrittenView* w : {&w1, &w2}) {
      if (w == &w1) {
        for (game::Policy* p : {a.get(), b.get(), pure.get(), prop.get(), default_gain.get()}) p->begin_episode(w->view, false);
      }
      sa = a->act(w->view), sb = b->act(w->view), sp = pure->act(w->view), sn = prop->act(w->view);
      sd = default_gain->act(w->view);
      ASSERT_EQ(sa.d_alpha, sb.d_alpha) << "episode " << e;
      ASSERT_EQ(sa.d_theta, sb.d_theta) << "episode " << e;
    }
    const bool is_pursuit = sa.d_alpha == sp.d_alpha && sa.d_theta == sp.d_theta;
    const bool is_pn = sa.d_alpha == sn.d_alpha && sa.d_theta == sn.d_theta;
    ASSERT_TRUE(is_pursuit || is_pn) << "episode " << e;
    if (is_pursuit == is_pn) continue;
    ++told;
    pursuit += is_pursuit;
    gain_differs += is_pn && (sd.d_alpha != sn.d_alpha || sd.d_theta != sn.d_theta);
  }
  ASSERT_GT(told, n / 4);
  EXPECT_NEAR(double(pursuit) / told, 0.75, 5 * std::sqrt(0.75 * 0.25 / told));
  EXPECT_GT(gain_differs, 0);  // pn played with the agent's gain 4.5, not the default
  // Another team seed draws otherwise.
  const auto c = saved->make(1, agent, Role::kPursuer, 78);
  Rng again(9);
  int differ = 0;
  const auto a2 = saved->make(1, agent, Role::kPursuer, 77);
  for (int e = 0; e < 200; ++e) {
    const testing::WrittenView w(random_saved_view(again));
    a2->begin_episode(w.view, false);
    c->begin_episode(w.view, false);
    const Steering x = a2->act(w.view), y = c->act(w.view);
    differ += x.d_alpha != y.d_alpha || x.d_theta != y.d_theta;
  }
  EXPECT_GT(differ, 0);
}

TEST(SavedPolicy, AMixtureIsAClassicPlayerInTheEpisodesItDrawsOne) {
  // pn and an MLP, drawn per episode: the mixture reports itself scripted (played free of the motion space) exactly
  // in the episodes whose actions are pn's, and not in those whose actions are the network's.
  const std::filesystem::path dir = temp("mixture_scripted");
  std::filesystem::create_directories(dir);
  write_mlp(dir / "net.json", "pursuer");
  write_mixture(dir / "mix.json", "pursuer", {{{"policy", "pn"}, {"weight", 1}}, {{"policy", "net.json"}, {"weight", 1}}});
  const AgentConfig agent = agent_preset("peg3d", Role::kPursuer);
  const auto mix = load_saved_policy(dir / "mix.json", Role::kPursuer)->make(1, agent, Role::kPursuer, 5);
  const auto net = load_saved_policy(dir / "net.json", Role::kPursuer)->make(1, agent, Role::kPursuer, 5);
  EXPECT_FALSE(net->scripted());
  Rng rng(4);
  std::array<int, 2> episodes{};
  for (int e = 0; e < 200; ++e) {
    const testing::WrittenView w(random_saved_view(rng));
    mix->begin_episode(w.view, false);
    const Steering m = mix->act(w.view), n = net->act(w.view);
    const bool network = m.d_alpha == n.d_alpha && m.d_theta == n.d_theta;
    ASSERT_EQ(mix->scripted(), !network) << "episode " << e;
    ++episodes[network];
  }
  EXPECT_GT(episodes[0], 50);
  EXPECT_GT(episodes[1], 50);
}

TEST(SavedPolicy, ABadMixtureFileIsRefusedNamingItsField) {
  const std::filesystem::path dir = temp("mixture_refusals");
  std::filesystem::create_directories(dir);
  write_mlp(dir / "net.json", "pursuer");
  write_mixture(dir / "inner.json", "pursuer", nlohmann::json::array({{{"policy", "pn"}, {"weight", 1}}}));
  const auto field_of = [&](const std::string& role, const nlohmann::json& members) {
    write_mixture(dir / "mix.json", role, members);
    try {
      load_saved_policy(dir / "mix.json", Role::kPursuer);
    } catch (const PolicyFormatError& e) {
      EXPECT_EQ(e.file(), dir / "mix.json") << e.what();
      return e.field();
    }
    return std::string("accepted");
  };
  const nlohmann::json pn = {{"policy", "pn"}, {"weight", 1}};
  EXPECT_EQ(field_of("pursuer", nlohmann::json::array({pn})), "accepted");
  EXPECT_EQ(field_of("evader", nlohmann::json::array({pn})), "role");
  EXPECT_EQ(field_of("pursuer", nlohmann::json::array()), "members");
  EXPECT_EQ(field_of("pursuer", {pn, {{"policy", "flee"}, {"weight", 1}}}), "members.1.policy");
  EXPECT_EQ(field_of("pursuer", {pn, {{"policy", "no-such-player"}, {"weight", 1}}}), "members.1.policy");
  EXPECT_EQ(field_of("pursuer", {pn, {{"policy", "facl"}, {"weight", 1}}}), "members.1.policy");
  EXPECT_EQ(field_of("pursuer", {pn, {{"policy", "inner.json"}, {"weight", 1}}}), "members.1.policy");
  EXPECT_EQ(field_of("pursuer", {pn, {{"policy", "net.json"}, {"weight", -1}}}), "members.1.weight");
  EXPECT_EQ(field_of("pursuer", {pn, {{"policy", "net.json"}, {"weight", "1"}}}), "members.1.weight");
  EXPECT_EQ(field_of("pursuer", {pn, {{"policy", "net.json"}}}), "members.1.weight");
  EXPECT_EQ(field_of("pursuer", nlohmann::json::array({{{"policy", "pn"}, {"weight", 0}}})), "members");
  EXPECT_EQ(field_of("pursuer", {{{"policy", "pn"}, {"weight", 1e308}}, {{"policy", "pn"}, {"weight", 1e308}}}), "members");
  EXPECT_EQ(field_of("pursuer", std::vector<nlohmann::json>(std::size_t(kMaxMixtureMembers) + 1, pn)), "members");
  EXPECT_EQ(field_of("pursuer", std::vector<nlohmann::json>(std::size_t(kMaxMixtureMembers), pn)), "accepted");
  // A member file that is not there names that file.
  write_mixture(dir / "mix.json", "pursuer", {pn, {{"policy", "missing.json"}, {"weight", 1}}});
  try {
    load_saved_policy(dir / "mix.json", Role::kPursuer);
    ADD_FAILURE() << "a missing member file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace peg3d::players
