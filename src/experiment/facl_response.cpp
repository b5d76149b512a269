#include "experiment/facl_response.hpp"

#include <memory>

#include "core/random.hpp"
#include "core/validation.hpp"
#include "game/episode.hpp"
#include "game/scenario_choice.hpp"
#include "players/registry.hpp"

namespace peg3d::experiment {
namespace {

/// An opponent as an evaluation plays it, inside a learning episode: told that nobody learns, taught nothing (a
/// frozen FACL or a network could not learn, and a classic player has nothing to learn).
class Unlearning final : public game::Policy {
 public:
  explicit Unlearning(std::unique_ptr<game::Policy> inner) : inner_(std::move(inner)) {}
  void begin_episode(const game::AgentView& view, bool) override { inner_->begin_episode(view, false); }
  Steering act(const game::AgentView& view) override { return inner_->act(view); }
  void learn(double, const game::AgentView&, bool) override {}
  bool scripted() const override { return inner_->scripted(); }

 private:
  std::unique_ptr<game::Policy> inner_;
};

}  // namespace

game::GameConfig with_opponent_config(game::GameConfig config, game::Role role, int count,
                                      const players::SavedPolicy& opponent) {
  if (const game::AgentConfig* own = opponent.config()) {
    for (int k = 0; k < count; ++k) config.set_agent(role, k, *own);
  }
  return config;
}

players::RoleModels train_facl_response(const game::Sim& sim, game::Role role, const players::SavedPolicy& opponent,
                                        const FaclResponseSettings& settings) {
  require_in_range("episodes", settings.episodes, 1, 10'000'000);
  const auto& all = sim.arena().map().scenarios;
  std::vector<const world::Scenario*> scenarios;
  for (const int i : game::scenarios_of_one_team_size(sim.arena().map(), settings.scenarios, "scenarios")) {
    scenarios.push_back(&all[std::size_t(i)]);
  }
  const game::GameConfig& config = sim.config();
  const game::Role other = role == game::Role::kPursuer ? game::Role::kEvader : game::Role::kPursuer;
  const world::Scenario& first = *scenarios.front();
  const int learners = int(role == game::Role::kPursuer ? first.pursuers.size() : first.evaders.size());
  const int opponents = first.agents() - learners;
  for (int k = 0; k < learners; ++k) {
    if (config.agent(role, k).policy != players::kFacl) {
      throw InvalidParameter(std::string(game::to_string(role)) + ".policy", config.agent(role, k).policy,
                             "a FACL best response needs its role's agents to play facl");
    }
  }
  // One line-up for every episode: the learners' policies keep their models (and exploration engines) throughout,
  // the opponents' players draw a mixture's member per episode.
  players::RoleModels models;
  players::Lineup lineup;
  const std::uint64_t opponent_seed = derive_seed(settings.seed, {2});
  const auto add_opponents = [&] {
    for (int k = 0; k < opponents; ++k) {
      lineup.add(std::make_unique<Unlearning>(
          opponent.make(players::agent_seed(opponent_seed, k), config.agent(other, k), other, opponent_seed)));
    }
  };
  if (role == game::Role::kEvader) add_opponents();
  players::add_configured(lineup, config, role, learners, derive_seed(settings.seed, {1}), &models);
  if (role == game::Role::kPursuer) add_opponents();
  game::SimState state(sim);
  for (int e = 0; e < settings.episodes; ++e) {
    const world::Scenario& s = *scenarios[std::size_t(e) % scenarios.size()];
    game::play(sim, state, s, lineup.policies(), true, derive_seed(settings.seed, {3, std::uint64_t(e)}));
  }
  return models;
}

}  // namespace peg3d::experiment
