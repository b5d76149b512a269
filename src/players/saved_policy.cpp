#include "players/saved_policy.hpp"

#include <cassert>
#include <cmath>

#include <fmt/format.h>

#include "core/hash.hpp"
#include "core/input_files.hpp"  // json_line_of
#include "core/random.hpp"
#include "game/scenario_choice.hpp"
#include "players/policy_io.hpp"
#include "players/registry.hpp"

namespace peg3d::players {

namespace {

std::string hash_of(const std::string& canonical) {
  Fnv1a h;
  h.add_text(canonical);
  return fmt::format("fnv1a64:{:016x}", h.value());
}

constexpr const char* kMixtureFormat = "peg3d-mixture";

// A mixture file's player: one member per episode, drawn from the team's seed and the episode's number, so
// every agent of a team given one team seed plays the same member. It never learns.
class MixturePolicy final : public game::Policy {
 public:
  MixturePolicy(std::vector<std::unique_ptr<game::Policy>> members, std::vector<double> weights, std::uint64_t team_seed)
      : members_(std::move(members)), weights_(std::move(weights)), team_seed_(team_seed) {}
  void begin_episode(const game::AgentView& view, bool learning) override {
    current_ = draw_member(weights_, derive_seed(team_seed_, {episode_++}));
    members_[std::size_t(current_)]->begin_episode(view, learning);
  }
  Steering act(const game::AgentView& view) override { return members_[std::size_t(current_)]->act(view); }
  bool scripted() const override { return members_[std::size_t(current_)]->scripted(); }

 private:
  std::vector<std::unique_ptr<game::Policy>> members_;
  std::vector<double> weights_;
  std::uint64_t team_seed_;
  std::uint64_t episode_ = 0;
  int current_ = 0;
};

// A peg3d-mixture document: {"format", "version": 1, "role", "members": [{"policy": NAME or FILE, "weight"}]}.
void read_mixture(SavedPolicy& p, const PolicyDocument& d, const std::filesystem::path& file, game::Role role) {
  const nlohmann::json& doc = d.doc;
  const auto fail = [&](const std::string& field, const std::string& message) {
    throw PolicyFormatError(file, json_line_of(d.text, field.substr(field.rfind('.') + 1)), field, message);
  };
  if (!doc.contains("version") || doc["version"] != 1) fail("version", "a peg3d-mixture file of version 1");
  if (!doc.contains("role") || !doc["role"].is_string()) fail("role", "missing: pursuer or evader");
  if (doc["role"].get<std::string>() != game::to_string(role)) {
    fail("role", fmt::format("the mixture is for the {}, not the {}", doc["role"].get<std::string>(), game::to_string(role)));
  }
  if (!doc.contains("members") || !doc["members"].is_array() || doc["members"].empty()) {
    fail("members", "a list of at least one {\"policy\": name or file, \"weight\": number}");
  }
  if (doc["members"].size() > std::size_t(kMaxMixtureMembers)) {
    fail("members", fmt::format("{} members: a mixture has at most {}", doc["members"].size(), kMaxMixtureMembers));
  }
  for (std::size_t k = 0; k < doc["members"].size(); ++k) {
    const nlohmann::json& m = doc["members"][k];
    const std::string field = fmt::format("members.{}", k);
    if (!m.is_object() || !m.contains("policy") || !m["policy"].is_string()) fail(field + ".policy", "missing: a player or a policy file");
    if (!m.contains("weight") || !m["weight"].is_number()) fail(field + ".weight", "missing: a number >= 0");
    SavedPolicy::Member member;
    member.weight = m["weight"].get<double>();
    const std::string source = m["policy"].get<std::string>();
    if (source.ends_with(".json") || source.find('/') != std::string::npos) {
      const std::filesystem::path path = std::filesystem::path(source).is_absolute() ? std::filesystem::path(source)
                                                                                     : file.parent_path() / source;
      member.saved = load_saved_policy(path, role);
      if (!member.saved->members.empty()) fail(field + ".policy", source + " is a mixture: a member is a player or a FACL or MLP file");
    } else {
      const PlayerInfo* player = find_player(source);
      if (player == nullptr || !player->plays(role) || player->learns()) {
        fail(field + ".policy", fmt::format("\"{}\" is not a classic {} player ({})", source, game::to_string(role),
                                            player_names(role)));
      }
      member.player = std::string(player->name);
    }
    p.members.push_back(std::move(member));
  }
  if (const MixtureProblem problem = check_mixture(p.members); !problem.message.empty()) {
    if (problem.member < 0) fail("members", problem.message);
    fail(fmt::format("members.{}.{}", problem.member, problem.field), problem.message);
  }
  std::string canonical = doc.dump();
  for (const SavedPolicy::Member& m : p.members) canonical += "|" + (m.saved ? m.saved->content_hash : m.player);
  p.content_hash = hash_of(canonical);
}

}  // namespace

MixtureProblem check_mixture(std::span<const SavedPolicy::Member> members) {
  double total = 0.0;
  const game::AgentConfig* own = nullptr;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const SavedPolicy::Member& m = members[k];
    if (!std::isfinite(m.weight) || m.weight < 0.0) {
      return {int(k), "weight", fmt::format("{}: a member's weight is a finite number >= 0", m.weight)};
    }
    total += m.weight;
    if (!m.saved) continue;
    const std::string name = m.saved->file.filename().string();
    if (const game::AgentConfig* mine = m.saved->config()) {
      if (own != nullptr && !(*own == *mine)) {
        return {int(k), "policy",
                name + " carries another agent configuration than the mixture's first FACL member: a mixture's FACL "
                       "members play under one configuration"};
      }
      own = mine;
    }
  }
  if (!(total > 0.0) || !std::isfinite(total)) return {-1, "", fmt::format("total weight {}: the members' weights sum to a finite number > 0", total)};
  return {};
}

const game::AgentConfig* mixture_config(std::span<const SavedPolicy::Member> members) {
  for (const SavedPolicy::Member& m : members) {
    if (const game::AgentConfig* c = m.saved ? m.saved->config() : nullptr) return c;
  }
  return nullptr;
}

int draw_member(std::span<const double> weights, std::uint64_t bits) {
  double total = 0.0;
  for (const double w : weights) total += w;
  const double u = double(bits >> 11) * 0x1.0p-53 * total;
  double sum = 0.0;
  int chosen = -1;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    if (weights[k] <= 0.0) continue;
    chosen = int(k);  // the last member of positive weight takes what rounding leaves above the sum
    sum += weights[k];
    if (u < sum) break;
  }
  assert(chosen >= 0);
  return chosen;
}

const game::AgentConfig* SavedPolicy::config() const {
  return facl ? &facl->config() : mixture_config(members);
}

std::unique_ptr<game::Policy> SavedPolicy::make(std::uint64_t seed, const game::AgentConfig& agent, game::Role role,
                                                std::uint64_t team_seed) const {
  std::unique_ptr<game::Policy> player;
  if (facl) {
    player = std::make_unique<FaclPolicy>(facl);
  } else if (mlp) {
    player = std::make_unique<MlpPolicy>(mlp, seed);
  } else {
    std::vector<std::unique_ptr<game::Policy>> made;
    std::vector<double> weights;
    for (std::size_t k = 0; k < members.size(); ++k) {
      const Member& m = members[k];
      const std::uint64_t own = derive_seed(seed, {k});
      if (m.saved) {
        made.push_back(m.saved->make(own, agent, role, team_seed));
      } else {
        game::AgentConfig a = agent;
        a.policy = m.player;
        made.push_back(make_player(a, role, own));
      }
      weights.push_back(m.weight);
    }
    player = std::make_unique<MixturePolicy>(std::move(made), std::move(weights), team_seed);
  }
  player->set_file(file);
  return player;
}

void SavedPolicy::check_fits(const game::Sim& sim, game::Role role, int rank) const {
  if (mlp) fit_observation(*mlp, sim, role, rank, file);  // a FACL model plays on its percept, which every agent has
  for (const Member& m : members) {
    if (m.saved) m.saved->check_fits(sim, role, rank);
  }
}

void SavedPolicy::check_fits(const game::Sim& sim, game::Role role) const {
  const int most = game::most_agents(sim.arena().map(), role);
  for (int k = 0; k < most; ++k) check_fits(sim, role, k);
}

std::shared_ptr<const SavedPolicy> load_saved_policy(const std::filesystem::path& file, game::Role role) {
  const PolicyDocument d = read_policy_document(file);
  auto p = std::make_shared<SavedPolicy>();
  p->file = file;
  if (d.doc.is_object() && d.doc.value("format", "") == kMixtureFormat) {
    read_mixture(*p, d, file, role);
  } else if (is_mlp_document(d.doc)) {
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

void add_saved(Lineup& lineup, const SavedPolicy& policy, const game::GameConfig& config, game::Role role, int count,
               std::uint64_t seed) {
  for (int k = 0; k < count; ++k) lineup.add(policy.make(agent_seed(seed, k), config.agent(role, k), role, seed));
}

}  // namespace peg3d::players
