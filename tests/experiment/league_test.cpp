// The league (experiment/league_experiment.hpp): who plays, that every pairing meets at every start, that the
// games do not depend on threads or on who else is in the league, and that the matrix and findings count
// the games as they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "experiment/league_experiment.hpp"
#include "experiment/league_report.hpp"
#include "players/policy_io.hpp"
#include "test_arena.hpp"

namespace peg3d::experiment {
namespace {

using game::Role;

std::shared_ptr<const world::Arena> league_arena() {
  static const auto a = testing::make_arena(
      {20, 20, 10}, {}, {testing::scenario("S1", {2, 2, 5}, {12, 12, 5}), testing::scenario("S2", {18, 2, 5}, {8, 12, 5})});
  return a;
}

Algorithm algorithm(const std::string& name, const std::string& preset) {
  Algorithm a{name, trial_preset(preset)};
  a.config.game.time_limit = 20.0;
  return a;
}

LeagueSettings small(int threads = 1) {
  LeagueSettings s;
  s.sweep.seed = 3;
  s.sweep.repeats = 2;  // training seeds
  s.eval_seeds = 2;
  s.sweep.episodes = 4;
  s.sweep.threads = threads;
  return s;
}

League league(std::vector<Algorithm> algorithms, LeagueSettings s) {
  return League(league_arena(), {{"room", league_arena()}}, std::move(algorithms), std::move(s));
}

TEST(League, EntrantsAreTheTrainedPoliciesOfEverySeedThenTheClassicOnes) {
  std::vector<Algorithm> algs{algorithm("a", "peg3d"), algorithm("b", "robust")};
  algs[1].config.game.evader = game::scripted_agent(algs[1].config.game.evader, "flee");  // b trains no evader
  const LeagueSettings s = small();
  const auto p = league_entrants(algs, s, Role::kPursuer);
  const auto e = league_entrants(algs, s, Role::kEvader);
  const std::vector<std::string> p_names{"a#0", "a#1", "b#0", "b#1", "pure-pursuit", "pn", "apollonius"};
  const std::vector<std::string> e_names{"a#0", "a#1", "flee", "flee-apollonius", "random"};
  ASSERT_EQ(p.size(), p_names.size());
  ASSERT_EQ(e.size(), e_names.size());
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p[i].name, p_names[i]);
  for (std::size_t i = 0; i < e.size(); ++i) EXPECT_EQ(e[i].name, e_names[i]);
  EXPECT_EQ(p[3].group, "b");
  EXPECT_EQ(p[3].train_seed, 1);
  EXPECT_EQ(p[4].group, "pure-pursuit");
  EXPECT_EQ(p[4].algorithm, -1);
}

TEST(League, EveryPairingMeetsAtEveryStartAndSeedWhateverTheThreads) {
  League one = league({algorithm("a", "peg3d")}, small(1));
  League two = league({algorithm("a", "peg3d")}, small(2));
  const auto g1 = one.run(true);
  const auto g2 = two.run(true);
  // 2 trained + 3 classic per role, 2 starts x 2 evaluation seeds.
  ASSERT_EQ(g1.size(), 5u * 5u * 2u * 2u);
  EXPECT_EQ(g1.size(), one.games());
  ASSERT_EQ(g1.size(), g2.size());
  for (std::size_t i = 0; i < g1.size(); ++i) {
    EXPECT_EQ(g1[i].pursuer, g2[i].pursuer);
    EXPECT_EQ(g1[i].evader, g2[i].evader);
    EXPECT_EQ(g1[i].result.steps, g2[i].result.steps) << i;
    EXPECT_EQ(g1[i].result.final_distance, g2[i].result.final_distance) << i;
    EXPECT_EQ(g1[i].result.evader_return, g2[i].result.evader_return) << i;
  }
  // Trained policies of different seeds differ.
  const auto& m0 = one.models(0, 0, Role::kPursuer).models.at(0)->tables(0).actor_table();
  const auto& m1 = one.models(0, 1, Role::kPursuer).models.at(0)->tables(0).actor_table();
  EXPECT_FALSE(std::equal(m0.begin(), m0.end(), m1.begin()));
}

TEST(League, ClassicGamesDoNotDependOnWhoElsePlays) {
  // The game at a start and seed is seeded by the start alone: adding an algorithm to the league leaves the
  // classic-against-scripted games as they were, so every pairing at one start is a paired comparison.
  const auto small_league = league({algorithm("a", "peg3d")}, small()).run(true);
  const auto big_league = league({algorithm("a", "peg3d"), algorithm("b", "robust")}, small()).run(true);
  int compared = 0;
  for (const auto& g : small_league) {
    if (g.pursuer.find('#') != std::string::npos || g.evader.find('#') != std::string::npos) continue;
    for (const auto& h : big_league) {
      if (h.map == g.map && h.scenario == g.scenario && h.eval_seed == g.eval_seed && h.pursuer == g.pursuer &&
          h.evader == g.evader) {
        EXPECT_EQ(h.result.steps, g.result.steps);
        EXPECT_EQ(h.result.final_distance, g.result.final_distance);
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 3 * 3 * 2 * 2);
}

TEST(League, EachTrainedSideChoosesItsOpponentsAsItsAlgorithmDoes) {
  // The rules are the first algorithm's, but whom a team plays against is its own strategy: b's pursuers keep
  // their assigned targets and a's evaders their assigned threats wherever they play; the classic policies take
  // the rules' choice.
  std::vector<Algorithm> algs{algorithm("a", "peg3d"), algorithm("b", "peg3d")};
  algs[0].config.game.team.evader_threat = game::OpponentChoice::kAssigned;
  algs[1].config.game.team.pursuer_target = game::OpponentChoice::kAssigned;
  League l = league(algs, small());
  const int classic = 2;  // the first classic group of either role
  for (const int e : {0, 1, classic}) {
    EXPECT_EQ(l.game_config(0, 0, e).team.pursuer_target, game::OpponentChoice::kNearest) << e;
    EXPECT_EQ(l.game_config(0, 1, e).team.pursuer_target, game::OpponentChoice::kAssigned) << e;
    EXPECT_EQ(l.game_config(0, classic, e).team.pursuer_target, game::OpponentChoice::kNearest) << e;
  }
  for (const int p : {0, 1, classic}) {
    EXPECT_EQ(l.game_config(0, p, 0).team.evader_threat, game::OpponentChoice::kAssigned) << p;
    EXPECT_EQ(l.game_config(0, p, 1).team.evader_threat, game::OpponentChoice::kNearest) << p;
    EXPECT_EQ(l.game_config(0, p, classic).team.evader_threat, game::OpponentChoice::kAssigned) << p;
  }
}

TEST(League, TrainingStartsWithTheTrainHeadingInsteadOfTheAlgorithms) {
  // The trained pursuer's tables after training: with train_heading nullopt the algorithm's own
  // initial_heading applies, so an algorithm set to random matches train_heading = random on a chase one.
  const auto pursuer_table = [](const Algorithm& a, std::optional<game::InitialHeading> heading) {
    LeagueSettings s = small();
    s.sweep.repeats = 1;
    s.train_heading = heading;
    League l = league({a}, s);
    l.run(true);
    const auto table = l.models(0, 0, Role::kPursuer).models.at(0)->tables(0).actor_table();
    return std::vector<double>(table.begin(), table.end());
  };
  Algorithm chase = algorithm("a", "peg3d"), random = chase;
  ASSERT_EQ(chase.config.game.initial_heading, game::InitialHeading::kChase);
  random.config.game.initial_heading = game::InitialHeading::kRandom;
  const auto from_chase = pursuer_table(chase, std::nullopt);
  const auto from_random = pursuer_table(chase, game::InitialHeading::kRandom);
  EXPECT_NE(from_chase, from_random);
  EXPECT_EQ(pursuer_table(random, std::nullopt), from_random);
  EXPECT_EQ(LeagueSettings{}.train_heading, game::InitialHeading::kRandom);  // the league's default
}

TEST(League, MatrixCountsTheGamesOfEachPairing) {
  League l = league({algorithm("a", "peg3d")}, small());
  const auto games = l.run(true);
  const auto groups = league_matrix(l, games, true);
  const auto entrants = league_matrix(l, games, false);
  EXPECT_EQ(groups.size(), 4u * 4u);    // a, pure-pursuit, pn, apollonius x a, flee, flee-apollonius, random
  EXPECT_EQ(entrants.size(), 5u * 5u);  // a#0 and a#1 apart
  for (const auto& r : groups) {
    std::size_t n = 0, captured = 0;
    double survival = 0.0;
    for (const auto& g : games) {
      const bool p = g.pursuer == r["pursuer"] || g.pursuer.rfind(r["pursuer"].get<std::string>() + "#", 0) == 0;
      const bool e = g.evader == r["evader"] || g.evader.rfind(r["evader"].get<std::string>() + "#", 0) == 0;
      if (!p || !e) continue;
      ++n;
      captured += g.result.captured();
      survival += g.result.duration;  // 1 v 1: the capture time or the game's end, both its duration
    }
    EXPECT_EQ(r["games"].get<std::size_t>(), n);
    EXPECT_EQ(r["captures"].get<std::size_t>(), captured);
    EXPECT_NEAR(r["evader_survival_s"]["mean"].get<double>(), survival / n, 1e-9);
  }
}

TEST(League, FindingsCompareWithTheBestClassicOpponent) {
  League l = league({algorithm("a", "peg3d")}, small());
  // Made-up games at one start: pure pursuit catches flee in 30 s, pn does not; a#0 catches it in 50 s and
  // a#1 does not. Against pure pursuit, flee lasts 30 s and a#0 and a#1 last 40 s and 20 s (mean 30).
  const auto game = [](const char* p, const char* e, bool captured, double t) {
    League::Game g{"room", "S1", 0, p, e, {}};
    g.result.outcome = captured ? game::Outcome::kCapture : game::Outcome::kTimeout;
    g.result.duration = t;
    g.result.captures = captured;
    g.result.capture_time_sum = captured ? t : 0.0;
    return g;
  };
  const std::vector<League::Game> games{game("pure-pursuit", "flee", true, 30), game("pn", "flee", false, 20),
                                        game("a#0", "flee", true, 50), game("a#1", "flee", false, 20),
                                        game("pure-pursuit", "a#0", true, 40), game("pure-pursuit", "a#1", true, 20)};
  const auto f = league_findings(l, games);
  const auto& vs_flee = f["pursuers"][0]["against_scripted_evaders"][0];
  EXPECT_EQ(vs_flee["evader"], "flee");
  EXPECT_EQ(vs_flee["best_classic_pursuer"], "pure-pursuit");
  EXPECT_DOUBLE_EQ(vs_flee["capture_rate"]["rate"].get<double>(), 0.5);
  EXPECT_FALSE(vs_flee["at_least_as_often"].get<bool>());
  const auto& vs_pp = f["evaders"][0]["against_classic_pursuers"][0];
  EXPECT_EQ(vs_pp["pursuer"], "pure-pursuit");
  EXPECT_EQ(vs_pp["best_scripted_evader"], "flee");
  EXPECT_EQ(vs_pp["paired_starts"].get<std::size_t>(), 1u);
  EXPECT_DOUBLE_EQ(vs_pp["survival_s"]["mean"].get<double>(), 30.0);
  EXPECT_DOUBLE_EQ(vs_pp["mean_difference_s"].get<double>(), 0.0);
  EXPECT_FALSE(vs_pp["survives_longer"].get<bool>());
}

TEST(League, ASavedEntrantPlaysAsTheTrainedPolicyItWasSavedFrom) {
  // Save a#0's trained pursuer and evader and enter them again, as files: at every start and seed they play the
  // games a#0 plays, bit for bit, after the classic entrants.
  League first = league({algorithm("a", "peg3d")}, small());
  const auto first_games = first.run(true);
  const auto dir = std::filesystem::path(::testing::TempDir());
  players::save_policy(dir / "league_p.json", *first.models(0, 0, Role::kPursuer).models.at(0));
  players::save_policy(dir / "league_e.json", *first.models(0, 0, Role::kEvader).models.at(0));
  LeagueSettings s = small();
  s.saved_pursuers = {{"saved_p", players::load_saved_policy(dir / "league_p.json", Role::kPursuer)}};
  s.saved_evaders = {{"saved_e", players::load_saved_policy(dir / "league_e.json", Role::kEvader)}};
  League second = league({algorithm("a", "peg3d")}, s);
  EXPECT_EQ(second.pursuers().back().name, "saved_p");
  EXPECT_EQ(second.pursuers().back().group, "saved_p");
  EXPECT_EQ(second.evaders().back().name, "saved_e");
  const auto games = second.run(true);
  ASSERT_EQ(games.size(), 6u * 6u * 2u * 2u);
  const auto find = [](const std::vector<League::Game>& all, const League::Game& like, const std::string& p,
                       const std::string& e) -> const League::Game* {
    for (const auto& g : all)
      if (g.scenario == like.scenario && g.eval_seed == like.eval_seed && g.pursuer == p && g.evader == e) return &g;
    return nullptr;
  };
  int compared = 0;
  for (const auto& g : first_games) {
    if (g.pursuer != "a#0" && g.evader != "a#0") continue;
    const std::string p = g.pursuer == "a#0" ? "saved_p" : g.pursuer, e = g.evader == "a#0" ? "saved_e" : g.evader;
    const League::Game* h = find(games, g, p, e);
    ASSERT_NE(h, nullptr) << p << " vs " << e;
    EXPECT_EQ(h->result.steps, g.result.steps) << p << " vs " << e;
    EXPECT_EQ(h->result.final_distance, g.result.final_distance) << p << " vs " << e;
    ++compared;
  }
  EXPECT_EQ(compared, (5 + 5 - 1) * 2 * 2);
  EXPECT_EQ(second.setup()["saved_pursuers"][0]["kind"], "facl");
  EXPECT_FALSE(first.setup().contains("saved_pursuers"));  // leagues without them keep their journal header
}

TEST(League, ASavedEntrantMustHaveANameOfItsOwn) {
  const auto file = std::filesystem::path(::testing::TempDir()) / "league_clash.json";
  players::save_policy(file, players::FaclModel(game::agent_preset("peg3d", Role::kPursuer), Role::kPursuer));
  LeagueSettings s = small();
  s.saved_pursuers = {{"pure-pursuit", players::load_saved_policy(file, Role::kPursuer)}};
  EXPECT_THROW(league({algorithm("a", "peg3d")}, s), InvalidParameter);
  s.saved_pursuers = {{"", players::load_saved_policy(file, Role::kPursuer)}};
  EXPECT_THROW(league({algorithm("a", "peg3d")}, s), InvalidParameter);
}

}  // namespace
}  // namespace peg3d::experiment
