#pragma once
// Matchups: every pursuer policy against every evader policy. The FACL agents are a co-trained pair (trained
// per scenario and seed, or loaded from policy files); the scripted ones are the classic guidance laws and
// evaders of game/scripted_policies.hpp. Each pairing plays one greedy episode per scenario and seed.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "game/episode.hpp"
#include "game/game_config.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

class ProgressReporter;

struct MatchupSettings {
  std::vector<std::string> pursuers{"facl", "pure-pursuit", "pn", "apollonius"};
  std::vector<std::string> evaders{"facl", "flee", "flee-apollonius", "random"};
  std::uint64_t seed = 1;
  int episodes = 200;  ///< FACL training episodes (ignored for a loaded policy)
  int repeats = 10;    ///< seeds per scenario
  int threads = 0;
  std::optional<std::filesystem::path> pursuer_policy;  ///< a saved FACL pursuer instead of training
  std::optional<std::filesystem::path> evader_policy;   ///< a saved FACL evader instead of training
};

struct MatchupRecord {
  std::string scenario;
  int repeat = 0;
  std::string pursuer, evader;
  game::EpisodeResult result;
};

/// The configuration a scripted policy plays with: the base agent's kinematics and guard, its own policy
/// name, no motion space and no learning.
game::AgentConfig scripted_agent(const game::AgentConfig& base, const std::string& policy);

std::vector<MatchupRecord> run_matchups(std::shared_ptr<const world::Arena> arena, const game::GameConfig& config,
                                        const MatchupSettings& settings, ProgressReporter* progress = nullptr);

void write_matchups_csv(const std::filesystem::path& file, const std::vector<MatchupRecord>& records);

/// Per pursuer and evader: runs, captures with a Wilson interval, mean capture time (captured runs), mean
/// pursuer path, collision runs, mean evader pinned fraction.
nlohmann::ordered_json summarize_matchups(const std::vector<MatchupRecord>& records, const MatchupSettings& settings);
std::string matchup_table(const nlohmann::ordered_json& summary);

}  // namespace peg3d::experiment
