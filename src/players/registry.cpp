#include "players/registry.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "players/facl_policy.hpp"
#include "players/scripted_policies.hpp"
#include "players/search_policies.hpp"

namespace peg3d::players {
namespace {

template <class P>
std::unique_ptr<game::Policy> plain(const game::AgentConfig&, game::Role, std::uint64_t) {
  return std::make_unique<P>();
}

// The table. Order: as listings and help texts show the players.
constexpr PlayerInfo kPlayers[] = {
    {kFacl, kBothRoles, 0, kNeedsTraining, "fuzzy actor-critic learning, the paper's learner (docs/learning.md)",
     [](const game::AgentConfig& c, game::Role role, std::uint64_t seed) -> std::unique_ptr<game::Policy> {
       return std::make_unique<FaclPolicy>(c, role, seed);
     }},
    {"pure-pursuit", kPursuers, kPursuers, kNeedsNothing, "heads straight at the evader", plain<PurePursuit>},
    {"pn", kPursuers, kPursuers, kNeedsNothing, "3D proportional navigation with gain pn_gain",
     [](const game::AgentConfig& c, game::Role, std::uint64_t) -> std::unique_ptr<game::Policy> {
       return std::make_unique<ProportionalNavigation>(c.pn_gain);
     }},
    {"voronoi", kPursuers, 0, kNeedsNothing,
     "a team shrinks the evader's Voronoi cell: each heads for the centre of the face it shares with it, else pn",
     [](const game::AgentConfig& c, game::Role, std::uint64_t) -> std::unique_ptr<game::Policy> {
       return std::make_unique<VoronoiPursuer>(c.pn_gain);
     }},
    {"voronoi-route", kPursuers, 0, kNeedsSight,
     "the partial game: voronoi, going round the solids by a grid of open cells where its straight way is blocked",
     [](const game::AgentConfig& c, game::Role, std::uint64_t) -> std::unique_ptr<game::Policy> {
       return std::make_unique<VoronoiPursuer>(c.pn_gain, VoronoiWay::kRoute);
     }},
    {"voronoi-geodesic", kPursuers, 0, kNeedsSight,
     "the partial game: voronoi-route with the cells by shortest ways round the solids (a geodesic partition)",
     [](const game::AgentConfig& c, game::Role, std::uint64_t) -> std::unique_ptr<game::Policy> {
       return std::make_unique<VoronoiPursuer>(c.pn_gain, VoronoiWay::kGeodesic);
     }},
    {"voronoi-intercept", kPursuers, 0, kNeedsSight,
     "the partial game: voronoi-geodesic, chasing toward where the evader's course meets its own instead of by pn",
     [](const game::AgentConfig& c, game::Role, std::uint64_t) -> std::unique_ptr<game::Policy> {
       return std::make_unique<VoronoiPursuer>(c.pn_gain, VoronoiWay::kGeodesic, VoronoiChase::kInterception);
     }},
    {"apollonius", kPursuers, kPursuers, kNeedsNothing, "aims at the Apollonius interception point", plain<ApolloniusInterceptor>},
    {"flee", kEvaders, kEvaders, kNeedsNothing, "flees along the line of sight, repelled by walls and obstacles",
     plain<FleeLineOfSight>},
    {"flee-apollonius", kEvaders, kEvaders, kNeedsNothing, "heads for the far side of its dominance region",
     plain<FleeApollonius>},
    {"random", kBothRoles, kEvaders, kNeedsNothing, "random steering within the bound",
     [](const game::AgentConfig& c, game::Role, std::uint64_t seed) -> std::unique_ptr<game::Policy> {
       return std::make_unique<RandomWalk>(c.steering, seed);
     }},
    {"search", kPursuers, 0, kNeedsSight,
     "the partial game: chases the evader in sight, else flies to its last sighting and searches", plain<SearchPursuer>},
    {"hide", kEvaders, 0, kNeedsSight, "the partial game: breaks the line of sight behind cover when seen, else flees",
     plain<HideEvader>},
};

}  // namespace

std::span<const PlayerInfo> registry() { return kPlayers; }

const PlayerInfo* find_player(std::string_view name) {
  for (const PlayerInfo& p : kPlayers) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

std::string player_names(game::Role role, unsigned excluding) {
  std::string names;
  for (const PlayerInfo& p : kPlayers) {
    if (p.plays(role) && (p.needs & excluding) == 0) names += (names.empty() ? "" : ", ") + std::string(p.name);
  }
  return names;
}

const PlayerInfo& player_named(std::string_view name, game::Role role, const std::string& field) {
  const PlayerInfo* p = find_player(name);
  if (p == nullptr || !p->plays(role)) {
    const std::string shown = name.size() <= 40 ? std::string(name) : std::string(name.substr(0, 37)) + "...";
    throw InvalidParameter(field, "\"" + shown + "\"",
                           fmt::format("must be {} policy: {}", role == game::Role::kPursuer ? "a pursuer" : "an evader",
                                       player_names(role)));
  }
  return *p;
}

std::vector<std::string> baseline_players(game::Role role) {
  std::vector<std::string> names;
  for (const PlayerInfo& p : kPlayers) {
    if ((p.baseline & role_set(role)) != 0) names.emplace_back(p.name);
  }
  return names;
}

std::string player_listing() {
  std::string out = fmt::format("{:<16} {:<16} {:<10} {}\n", "player", "roles", "needs", "what it does");
  for (const PlayerInfo& p : kPlayers) {
    const char* roles = p.roles == kBothRoles ? "pursuer, evader" : p.roles == kPursuers ? "pursuer" : "evader";
    const char* needs = p.learns() ? "training" : (p.needs & kNeedsSight) != 0 ? "sight" : "-";
    out += fmt::format("{:<16} {:<16} {:<10} {}\n", p.name, roles, needs, p.help);
  }
  return out;
}

std::unique_ptr<game::Policy> make_player(const game::AgentConfig& config, game::Role role, std::uint64_t seed) {
  return player_named(config.policy, role, "policy").make(config, role, seed);
}

bool learns(const game::AgentConfig& config) {
  const PlayerInfo* p = find_player(config.policy);
  return p != nullptr && p->learns();
}

void check_players(const game::GameConfig& config) {
  player_named(config.pursuer.policy, game::Role::kPursuer, "pursuer.policy");
  player_named(config.evader.policy, game::Role::kEvader, "evader.policy");
  for (std::size_t k = 0; k < config.pursuers.size(); ++k) {
    player_named(config.pursuers[k].policy, game::Role::kPursuer, fmt::format("pursuers.{}.policy", k));
  }
  for (std::size_t k = 0; k < config.evaders.size(); ++k) {
    player_named(config.evaders[k].policy, game::Role::kEvader, fmt::format("evaders.{}.policy", k));
  }
}

}  // namespace peg3d::players
