#include "players/saved_policy.hpp"

#include <fmt/format.h>

#include "core/hash.hpp"
#include "players/policy_io.hpp"

namespace peg3d::players {

namespace {

std::string hash_of(const std::string& canonical) {
  Fnv1a h;
  h.add_text(canonical);
  return fmt::format("fnv1a64:{:016x}", h.value());
}

}  // namespace

std::unique_ptr<game::Policy> SavedPolicy::make(std::uint64_t seed) const {
  std::unique_ptr<game::Policy> player;
  if (facl) {
    player = std::make_unique<FaclPolicy>(facl);
  } else {
    player = std::make_unique<MlpPolicy>(mlp, seed);
  }
  player->set_file(file);
  return player;
}

void SavedPolicy::check_fits(const game::Sim& sim, game::Role role, int rank) const {
  if (mlp) fit_observation(*mlp, sim, role, rank, file);  // a FACL model plays on its percept, which every agent has
}

void SavedPolicy::check_fits(const game::Sim& sim, game::Role role) const {
  std::size_t most = 0;
  for (const world::Scenario& s : sim.arena().map().scenarios) {
    most = std::max(most, role == game::Role::kPursuer ? s.pursuers.size() : s.evaders.size());
  }
  for (std::size_t k = 0; k < most; ++k) check_fits(sim, role, int(k));
}

std::shared_ptr<const SavedPolicy> load_saved_policy(const std::filesystem::path& file, game::Role role) {
  const PolicyDocument d = read_policy_document(file);
  auto p = std::make_shared<SavedPolicy>();
  p->file = file;
  if (is_mlp_document(d.doc)) {
    p->mlp = mlp_from_json(d.doc, file, role, d.text);
    p->content_hash = hash_of(d.doc.dump());
  } else {
    std::shared_ptr<const FaclModel> m = policy_from_json(d.doc, file, role, d.text);
    // The hash peg-matchup's journal has always recorded for a loaded FACL policy.
    p->content_hash = hash_of(policy_to_json(*m).dump());
    p->facl = std::move(m);
  }
  return p;
}

void add_saved(Lineup& lineup, const SavedPolicy& policy, int count, std::uint64_t seed) {
  for (int k = 0; k < count; ++k) lineup.add(policy.make(agent_seed(seed, k)));
}

}  // namespace peg3d::players
