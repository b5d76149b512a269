// The players' registry (players/registry.hpp): one table that names, checks, lists and builds every player.
#include "players/registry.hpp"

#include <gtest/gtest.h>

#include <set>

#include "core/config_fields.hpp"
#include "core/validation.hpp"
#include "players/facl_policy.hpp"
#include "players/scripted_policies.hpp"
#include "players/search_policies.hpp"

namespace peg3d::players {
namespace {

using game::Role;

TEST(PlayerRegistry, NamesAreUniqueWordsAndEveryPlayerPlaysARole) {
  std::set<std::string_view> names;
  for (const PlayerInfo& p : registry()) {
    EXPECT_TRUE(config::is_name(p.name)) << p.name;
    EXPECT_TRUE(names.insert(p.name).second) << p.name << " twice";
    EXPECT_NE(p.roles & kBothRoles, 0u) << p.name;
    EXPECT_EQ(p.baseline & ~p.roles, 0u) << p.name << " is a baseline of a role it does not play";
    EXPECT_FALSE(p.help.empty()) << p.name;
    EXPECT_EQ(find_player(p.name), &p);
  }
  EXPECT_EQ(find_player("teleport"), nullptr);
}

TEST(PlayerRegistry, ANameIsCheckedForItsRole) {
  EXPECT_EQ(player_named("pn", Role::kPursuer, "--pursuers").name, "pn");
  EXPECT_EQ(player_named("random", Role::kEvader, "--evaders").name, "random");
  for (const auto& [name, role] : {std::pair{"flee", Role::kPursuer}, std::pair{"teleport", Role::kEvader},
                                   std::pair{"search", Role::kEvader}}) {
    try {
      player_named(name, role, "--flag");
      ADD_FAILURE() << name;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.parameter(), "--flag");
      // The message lists the role's players, from the table.
      EXPECT_NE(std::string(e.what()).find(player_names(role)), std::string::npos) << e.what();
    }
  }
}

TEST(PlayerRegistry, TheFactoryBuildsTheNamedPlayer) {
  game::AgentConfig c;
  const auto built = [&](const char* name, Role role) {
    c.policy = name;
    return make_player(c, role, 7);
  };
  EXPECT_NE(dynamic_cast<FaclPolicy*>(built("facl", Role::kEvader).get()), nullptr);
  EXPECT_NE(dynamic_cast<ProportionalNavigation*>(built("pn", Role::kPursuer).get()), nullptr);
  EXPECT_NE(dynamic_cast<VoronoiPursuer*>(built("voronoi", Role::kPursuer).get()), nullptr);
  EXPECT_NE(dynamic_cast<VoronoiPursuer*>(built("voronoi-route", Role::kPursuer).get()), nullptr);
  EXPECT_NE(dynamic_cast<VoronoiPursuer*>(built("voronoi-geodesic", Role::kPursuer).get()), nullptr);
  EXPECT_NE(dynamic_cast<VoronoiPursuer*>(built("voronoi-intercept", Role::kPursuer).get()), nullptr);
  EXPECT_NE(dynamic_cast<RandomWalk*>(built("random", Role::kPursuer).get()), nullptr);
  EXPECT_NE(dynamic_cast<SearchPursuer*>(built("search", Role::kPursuer).get()), nullptr);
  EXPECT_NE(dynamic_cast<HideEvader*>(built("hide", Role::kEvader).get()), nullptr);
  EXPECT_THROW(built("hide", Role::kPursuer), InvalidParameter);
  EXPECT_TRUE(learns(c = game::AgentConfig{}));
}

TEST(PlayerRegistry, EveryPlayerButTheLearnerIsAClassicPlayer) {
  // The game plays classic players free of the motion space (game::begin_playing): every non-learning player is one.
  for (const PlayerInfo& p : registry()) {
    game::AgentConfig c;
    c.policy = std::string(p.name);
    const Role role = (p.roles & kPursuers) != 0 ? Role::kPursuer : Role::kEvader;
    EXPECT_EQ(make_player(c, role, 3)->scripted(), !p.learns()) << p.name;
  }
}

TEST(PlayerRegistry, BaselinesAreTheDefaultLineUps) {
  EXPECT_EQ(baseline_players(Role::kPursuer), (std::vector<std::string>{"pure-pursuit", "pn", "apollonius"}));
  EXPECT_EQ(baseline_players(Role::kEvader), (std::vector<std::string>{"flee", "flee-apollonius", "random"}));
  EXPECT_EQ(player_names(Role::kPursuer), "facl, pure-pursuit, pn, voronoi, voronoi-route, voronoi-geodesic, voronoi-intercept, apollonius, random, search");
  EXPECT_EQ(player_names(Role::kEvader, kNeedsSight), "facl, flee, flee-apollonius, random");
}

TEST(PlayerRegistry, EveryAgentOfAConfigurationIsChecked) {
  game::GameConfig c = game::preset("peg3d");
  check_players(c);
  for (const auto& [field, edit] : std::vector<std::pair<std::string, void (*)(game::GameConfig&)>>{
           {"pursuer.policy", [](game::GameConfig& g) { g.pursuer.policy = "flee"; }},
           {"evader.policy", [](game::GameConfig& g) { g.evader.policy = "pure-pursuit"; }},
           {"evaders.0.policy", [](game::GameConfig& g) { g.evaders = {g.evader}, g.evaders[0].policy = "apollonius"; }},
           {"pursuers.1.policy", [](game::GameConfig& g) { g.pursuers = {g.pursuer, g.pursuer}, g.pursuers[1].policy = "x"; }}}) {
    game::GameConfig bad = c;
    edit(bad);
    try {
      check_players(bad);
      ADD_FAILURE() << field;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.parameter(), field) << e.what();
    }
  }
}

TEST(PlayerRegistry, TheListingHasALinePerPlayer) {
  const std::string listing = player_listing();
  for (const PlayerInfo& p : registry()) {
    EXPECT_NE(listing.find(std::string(p.name) + " "), std::string::npos) << p.name;
    EXPECT_NE(listing.find(std::string(p.help)), std::string::npos) << p.name;
  }
}

}  // namespace
}  // namespace peg3d::players
