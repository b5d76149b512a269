#pragma once
// Matchups: every pursuer policy against every evader policy, with every agent of a role playing that
// policy (teams of one policy each). The FACL agents are a co-trained set (trained per scenario and seed, or
// loaded from policy files); the scripted ones are the classic guidance laws and evaders of
// players/scripted_policies.hpp. Each pairing plays one greedy episode per scenario and seed.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/experiment.hpp"
#include "experiment/sweep_settings.hpp"
#include "experiment/training.hpp"
#include "experiment/trial_config.hpp"
#include "game/episode.hpp"
#include "players/facl_policy.hpp"
#include "players/saved_policy.hpp"
#include "game/game_config.hpp"
#include "game/sim.hpp"
#include "world/arena.hpp"

namespace peg3d::experiment {

/// FACL, then the baseline players of `role` (players::baseline_players): the match-ups' default.
std::vector<std::string> default_players(game::Role role);

struct MatchupSettings {
  /// The players of each role (players/registry.hpp): by default FACL and the role's baselines.
  std::vector<std::string> pursuers = default_players(game::Role::kPursuer);
  std::vector<std::string> evaders = default_players(game::Role::kEvader);
  /// Seeds, budget (FACL training episodes, ignored for a loaded policy), repeats (seeds per scenario, 10 by
  /// default), threads and control.
  SweepSettings sweep{.repeats = 10};
  /// A saved pursuer (FACL or MLP) playing the "facl" slot instead of a trained one (every pursuer plays it);
  /// results name the slot by its kind ("facl" or "mlp").
  std::shared_ptr<const players::SavedPolicy> pursuer_policy{};
  std::shared_ptr<const players::SavedPolicy> evader_policy{};  ///< the same for the evaders
  /// The classic opponents mixed into FACL training (experiment/training.hpp); null: co-learning.
  std::shared_ptr<const OpponentPool> pool{};
  /// Chooses the games (by matchup_key) whose episode is recorded, for replay viewers; none when empty.
  std::function<bool(const std::string&)> keep_trace{};
  /// Chooses the games (by matchup_key) whose agents' own maps are written at the episode's end, as OctoMap
  /// `.bt` files `<maps_dir>/<key>_<agent>.bt` (an agent without a map writes none); none when empty.
  std::function<bool(const std::string&)> keep_maps{};
  std::filesystem::path maps_dir{};
};

struct MatchupRecord {
  std::string scenario;
  int repeat = 0;
  std::string pursuer, evader;  ///< policy names
  game::EpisodeResult result;
  std::vector<game::AgentSummary> agents;
  std::shared_ptr<const game::Trace> trace;  ///< every instant, when settings.keep_trace chose the game
};

/// The name results give a pairing's player of `role`: its name, except that the "facl" slot played by a saved
/// policy is named by that policy's kind ("facl" or "mlp").
std::string matchup_policy_name(const MatchupSettings& settings, game::Role role, const std::string& player);

/// A game's key: SCENARIO_rREPEAT_PURSUER_vs_EVADER, e.g. S1_r0_pn_vs_flee.
std::string matchup_key(const MatchupRecord& r);

/// The game configuration of one pairing: `base` with the pursuers' and evaders' players replaced.
game::GameConfig pairing_config(const game::GameConfig& base, const std::string& pursuer, const std::string& evader,
                                const MatchupSettings& settings);

/// Every Sim the matchups need, built (and the map's scenarios checked) before any run: [0] trains, then
/// one per pursuer x evader pairing, pursuer-major.
std::vector<game::Sim> make_matchup_sims(const std::shared_ptr<const world::Arena>& arena, const game::GameConfig& base,
                                         const MatchupSettings& settings);

/// Runs in the sweep (scenarios x repeats); run i is scenario i / repeats, repeat i % repeats, and plays every
/// pairing.
std::size_t matchup_run_count(const world::Arena& arena, const MatchupSettings& settings);

/// Everything the sweep's results depend on, for its journal header and run_info.json: the experiment, the
/// peg3d build, the map's content hash, seed, episodes, repeats, pursuer and evader policies, the content
/// hashes of loaded policies, and the base configuration.
nlohmann::json matchup_setup(const world::Arena& arena, const TrialConfig& base, const MatchupSettings& settings);

/// The seeds of run_info.json: the root, how seeds derive, and each run's seed.
nlohmann::ordered_json matchup_seeds(const world::Arena& arena, const MatchupSettings& settings);

/// matchups.csv: one row per game (scenario, repeat, pursuer, evader, then the episode columns).
void write_matchups_csv(const std::filesystem::path& file, const std::vector<MatchupRecord>& records);
/// agents.csv: one row per agent per game (docs/results.md).
void write_matchup_agents_csv(const std::filesystem::path& file, const std::vector<MatchupRecord>& records);

/// Per pursuer and evader policy: games, games with every evader captured (Wilson interval), evaders captured
/// (Wilson interval), mean time to each capture and to the last, mean paths, collision runs, evader pinned
/// fraction.
nlohmann::ordered_json summarize_matchups(const std::vector<MatchupRecord>& records, const MatchupSettings& settings);
std::string matchup_table(const nlohmann::ordered_json& summary);

class MatchupRun;

/// The matchups as an Experiment: run i (scenario i / repeats, repeat i % repeats) trains the FACL agents of
/// its start when a "facl" slot needs them, then plays every pairing, pursuer-major. Result files
/// (docs/results.md): matchups.csv, agents.csv, summary.json.
class MatchupExperiment : public Experiment {
 public:
  /// Builds every Sim (make_matchup_sims, each checking the map's starts) and, unless settings.pool is set, the
  /// classic opponents FACL training mixes in.
  MatchupExperiment(std::shared_ptr<const world::Arena> arena, TrialConfig base, MatchupSettings settings);
  ~MatchupExperiment() override;

  std::string kind() const override { return "matchup"; }
  nlohmann::json setup() const override { return matchup_setup(*arena_, base_, settings_); }
  std::size_t run_count() const override { return matchup_run_count(*arena_, settings_); }
  std::size_t episodes_per_run() const override;
  void begin(const sweep::SweepControl& control) override;
  void run_one(std::size_t i) override;
  nlohmann::json encode(std::size_t i) const override;
  void restore(std::size_t i, const nlohmann::json& record) override;
  void finish(bool root) override;
  void record_episodes(std::function<bool(const std::string&)> chosen) override { settings_.keep_trace = std::move(chosen); }
  void write_results(const std::filesystem::path& out, const SweepTiming& timing) const override;
  std::vector<std::pair<std::string, const world::Arena*>> maps() const override { return {{"map", arena_.get()}}; }
  nlohmann::ordered_json run_info() const override;
  std::vector<RecordedEpisode> recorded() const override;
  std::string report(const SweepTiming& timing) const override;

  /// Every game, in run order then pairing order, once finish(true) has gathered them.
  const std::vector<MatchupRecord>& records() const { return records_; }

 private:
  std::size_t pairings() const { return settings_.pursuers.size() * settings_.evaders.size(); }

  std::shared_ptr<const world::Arena> arena_;
  TrialConfig base_;
  MatchupSettings settings_;
  std::vector<game::Sim> sims_;  ///< [0] trains, then one per pairing (make_matchup_sims)
  std::unique_ptr<const MatchupRun> play_;
  std::vector<std::vector<MatchupRecord>> per_run_;
  std::vector<MatchupRecord> records_;
  nlohmann::ordered_json summary_;
};

}  // namespace peg3d::experiment
