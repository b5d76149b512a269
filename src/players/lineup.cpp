#include "players/lineup.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/random.hpp"
#include "players/registry.hpp"

namespace peg3d::players {

std::uint64_t agent_seed(std::uint64_t role_seed, int k) {
  return k == 0 ? role_seed : derive_seed(role_seed, {static_cast<std::uint64_t>(k)});
}

std::shared_ptr<const FaclModel> RoleModels::for_agent(int k) const {
  if (of_agent.empty()) return nullptr;
  const int m = of_agent[std::size_t(std::min<int>(k, static_cast<int>(of_agent.size()) - 1))];
  return m >= 0 ? models[std::size_t(m)] : nullptr;
}

void Lineup::add(std::unique_ptr<game::Policy> policy) {
  pointers_.push_back(policy.get());
  owned_.push_back(std::move(policy));
}

void add_configured(Lineup& lineup, const game::GameConfig& config, game::Role role, int count, std::uint64_t seed,
                    RoleModels* models) {
  RoleModels local;
  RoleModels& m = models != nullptr ? *models : local;
  m.models.clear();
  m.of_agent.assign(std::size_t(count), -1);
  for (int k = 0; k < count; ++k) {
    const game::AgentConfig& a = config.agent(role, k);
    if (!learns(a)) {
      lineup.add(make_player(a, role, agent_seed(seed, k)));
      continue;
    }
    int shared = -1;
    for (std::size_t j = 0; j < m.models.size(); ++j)
      if (m.models[j]->config() == a) shared = static_cast<int>(j);
    if (shared < 0) {
      m.models.push_back(std::make_shared<FaclModel>(a, role));
      shared = static_cast<int>(m.models.size()) - 1;
    }
    m.of_agent[std::size_t(k)] = shared;
    lineup.add(std::make_unique<FaclPolicy>(m.models[std::size_t(shared)], agent_seed(seed, k)));
  }
}

void add_frozen(Lineup& lineup, const RoleModels& models, int count) {
  for (int k = 0; k < count; ++k) {
    auto model = models.for_agent(k);
    if (!model) throw std::logic_error("no trained FACL model for this agent");
    lineup.add(std::make_unique<FaclPolicy>(std::move(model)));
  }
}

}  // namespace peg3d::players
