#include "experiment/matchup_experiment.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/config_json.hpp"
#include "core/random.hpp"
#include "experiment/trial.hpp"
#include "players/lineup.hpp"
#include "players/registry.hpp"
#include "results/codecs.hpp"
#include "results/csv_writer.hpp"
#include "results/result_files.hpp"
#include "results/run_info.hpp"
#include "results/statistics.hpp"
#include "sweep/progress_reporter.hpp"
#include "sweep/sweep_driver.hpp"

namespace peg3d::experiment {

std::vector<std::string> default_players(game::Role role) {
  std::vector<std::string> names{std::string(players::kFacl)};
  for (std::string& name : players::baseline_players(role)) names.push_back(std::move(name));
  return names;
}

game::GameConfig pairing_config(const game::GameConfig& base, const std::string& pursuer, const std::string& evader,
                                const MatchupSettings& s) {
  game::GameConfig c = base;
  const auto side = [&c](game::Role role, const std::string& player, const std::shared_ptr<const players::SavedPolicy>& loaded) {
    if (player != players::kFacl) {
      c = game::with_role_playing(std::move(c), role, player);
    } else if (loaded && loaded->config() != nullptr) {
      (role == game::Role::kPursuer ? c.pursuer : c.evader) = *loaded->config();
      (role == game::Role::kPursuer ? c.pursuers : c.evaders).clear();
    }
  };
  side(game::Role::kPursuer, pursuer, s.pursuer_policy);
  side(game::Role::kEvader, evader, s.evader_policy);
  return c;
}

std::vector<game::Sim> make_matchup_sims(const std::shared_ptr<const world::Arena>& arena, const game::GameConfig& base,
                                         const MatchupSettings& s) {
  std::vector<game::Sim> sims;
  sims.reserve(1 + s.pursuers.size() * s.evaders.size());
  sims.emplace_back(arena, base);
  for (const auto& p : s.pursuers)
    for (const auto& e : s.evaders) sims.emplace_back(arena, pairing_config(base, p, e, s));
  return sims;
}

std::size_t matchup_run_count(const world::Arena& arena, const MatchupSettings& s) {
  return arena.map().scenarios.size() * static_cast<std::size_t>(s.sweep.repeats);
}

nlohmann::json matchup_setup(const world::Arena& arena, const TrialConfig& base, const MatchupSettings& s) {
  nlohmann::json pursuers = nlohmann::json::array(), evaders = nlohmann::json::array();
  for (const auto& p : s.pursuers) pursuers.push_back(matchup_policy_name(s, game::Role::kPursuer, p));
  for (const auto& e : s.evaders) evaders.push_back(matchup_policy_name(s, game::Role::kEvader, e));
  const auto policy_hash = [](const std::shared_ptr<const players::SavedPolicy>& m) {
    return m ? nlohmann::json(m->content_hash) : nlohmann::json(nullptr);
  };
  nlohmann::json setup = setup_header("matchup", arena, s.sweep);
  setup["repeats"] = s.sweep.repeats;
  setup["pursuers"] = std::move(pursuers);
  setup["evaders"] = std::move(evaders);
  setup["pursuer_policy_hash"] = policy_hash(s.pursuer_policy);
  setup["evader_policy_hash"] = policy_hash(s.evader_policy);
  setup["config"] = config::to_json(base);
  return setup;
}

nlohmann::ordered_json matchup_seeds(const world::Arena& arena, const MatchupSettings& s) {
  return {{"root", s.sweep.seed},
          {"derivation", "run seed = derive_seed(root, {scenario index, repeat}); FACL training as a trial with the run "
                         "seed; pairing (p, e) = derive_seed(run seed, {10, p, e}) for the pursuers, derive_seed(that, "
                         "{1}) for the evaders, derive_seed(that, {2}) for the episode"},
          {"runs", scenario_run_seeds(arena.map().scenarios, s.sweep.repeats, s.sweep.seed)}};
}

std::string matchup_policy_name(const MatchupSettings& s, game::Role role, const std::string& player) {
  const auto& saved = role == game::Role::kPursuer ? s.pursuer_policy : s.evader_policy;
  return player == players::kFacl && saved ? saved->kind_name() : player;
}

namespace {

bool needs_training(const MatchupSettings& s) {
  for (const auto& p : s.pursuers)
    if (p == players::kFacl && !s.pursuer_policy) return true;
  for (const auto& e : s.evaders)
    if (e == players::kFacl && !s.evader_policy) return true;
  return false;
}

}  // namespace

// One run of the matchups: the FACL agents of a start (trained or loaded), then every pairing's greedy game.
class MatchupRun {
 public:
  MatchupRun(const std::vector<game::Sim>& sims, const MatchupSettings& s, const TrainingConfig& training)
      : sims_(sims), s_(s), training_(training), train_(needs_training(s)) {}

  std::vector<MatchupRecord> play(std::size_t i) const {
    const auto& scenarios = sims_.front().arena().map().scenarios;
    const int sc = static_cast<int>(i / s_.sweep.repeats), rep = static_cast<int>(i % s_.sweep.repeats);
    const world::Scenario& scenario = scenarios[std::size_t(sc)];
    const std::uint64_t seed = run_seed(s_.sweep.seed, sc, rep);
    players::RoleModels facl_pursuers, facl_evaders;
    if (train_) {
      TrialResult t = run_trial(sims_.front(), {.scenario = &scenario,
                                                .seed = seed,
                                                .episodes = s_.sweep.episodes,
                                                .stop = s_.sweep.control.stop,
                                                .training = training_,
                                                .pool = s_.pool.get(),
                                                .progress = s_.sweep.control.progress});
      facl_pursuers = std::move(t.pursuer_models);
      facl_evaders = std::move(t.evader_models);
    }
    game::SimState state(sims_.front());
    std::vector<MatchupRecord> records;
    for (std::size_t p = 0; p < s_.pursuers.size(); ++p) {
      for (std::size_t e = 0; e < s_.evaders.size(); ++e) {
        sweep::throw_if_stopped(s_.sweep.control.stop);
        records.push_back(play_pairing(p, e, scenario, rep, seed, facl_pursuers, facl_evaders, state));
        if (s_.sweep.control.progress) s_.sweep.control.progress->episode_done();
      }
    }
    return records;
  }

 private:
  // Pairing (p, e) at one start: its lineup (frozen FACL models or classic policies seeded from the run's
  // seed) and its greedy game.
  MatchupRecord play_pairing(std::size_t p, std::size_t e, const world::Scenario& scenario, int rep, std::uint64_t seed,
                             const players::RoleModels& facl_pursuers, const players::RoleModels& facl_evaders,
                             game::SimState& state) const {
    const game::Sim& sim = sims_[1 + p * s_.evaders.size() + e];
    const int pursuers = static_cast<int>(scenario.pursuers.size()), evaders = static_cast<int>(scenario.evaders.size());
    const std::uint64_t pseed = derive_seed(seed, {10, p, e});
    players::Lineup lineup;
    if (s_.pursuers[p] == players::kFacl && s_.pursuer_policy) {
      players::add_saved(lineup, *s_.pursuer_policy, sim.config(), game::Role::kPursuer, pursuers, pseed);
    } else if (s_.pursuers[p] == players::kFacl) {
      players::add_frozen(lineup, facl_pursuers, pursuers);
    } else {
      players::add_configured(lineup, sim.config(), game::Role::kPursuer, pursuers, pseed);
    }
    if (s_.evaders[e] == players::kFacl && s_.evader_policy) {
      players::add_saved(lineup, *s_.evader_policy, sim.config(), game::Role::kEvader, evaders, derive_seed(pseed, {1}));
    } else if (s_.evaders[e] == players::kFacl) {
      players::add_frozen(lineup, facl_evaders, evaders);
    } else {
      players::add_configured(lineup, sim.config(), game::Role::kEvader, evaders, derive_seed(pseed, {1}));
    }
    MatchupRecord record{scenario.name, rep, matchup_policy_name(s_, game::Role::kPursuer, s_.pursuers[p]),
                         matchup_policy_name(s_, game::Role::kEvader, s_.evaders[e]), {}, {}, {}};
    std::shared_ptr<game::Trace> trace;
    if (s_.keep_trace && s_.keep_trace(matchup_key(record))) {
      trace = std::make_shared<game::Trace>();
      trace->reserve(sim.max_steps(), scenario.agents());
    }
    state.forget_maps();  // persistent maps carry nothing from one pairing to the next
    record.result = evaluate(sim, state, scenario, lineup, derive_seed(pseed, {2}), trace.get());
    record.trace = std::move(trace);
    record.agents = game::agent_summaries(state);
    if (s_.keep_maps && s_.keep_maps(matchup_key(record))) {
      // Made here, by the first run that writes a map: by then every input was checked and OUT was made.
      std::filesystem::create_directories(s_.maps_dir);
      for (int i = 0; i < state.agent_count(); ++i) {
        const game::AgentState& a = state.agents[std::size_t(i)];
        if (const sense::ScanMap* map = state.map(i)) {
          map->write_bt(s_.maps_dir / (matchup_key(record) + "_" + game::agent_label(a.role, a.rank) + ".bt"));
        }
      }
    }
    return record;
  }

  const std::vector<game::Sim>& sims_;
  const MatchupSettings& s_;
  const TrainingConfig& training_;
  bool train_;
};

namespace {

nlohmann::json encode_games(const std::vector<MatchupRecord>& records) {
  nlohmann::json games = nlohmann::json::array();
  for (const MatchupRecord& r : records) {
    nlohmann::json agents = nlohmann::json::array();
    for (const auto& a : r.agents) agents.push_back(results::agent_summary_to_json(a));
    games.push_back({{"scenario", r.scenario},
                     {"repeat", r.repeat},
                     {"pursuer", r.pursuer},
                     {"evader", r.evader},
                     {"result", results::episode_to_json(r.result)},
                     {"agents", std::move(agents)}});
    if (r.trace) games.back()["trace"] = results::trace_to_json(*r.trace);
  }
  return nlohmann::json{{"games", std::move(games)}};
}

std::vector<MatchupRecord> restore_games(const nlohmann::json& data, std::size_t pairings) {
  std::vector<MatchupRecord> records;
  for (const auto& g : data.at("games")) {
    MatchupRecord r{g.at("scenario").get<std::string>(), g.at("repeat").get<int>(), g.at("pursuer").get<std::string>(),
                    g.at("evader").get<std::string>(), results::episode_from_json(g.at("result")), {}, {}};
    for (const auto& a : g.at("agents")) r.agents.push_back(results::agent_summary_from_json(a));
    if (g.contains("trace")) r.trace = std::make_shared<const game::Trace>(results::trace_from_json(g.at("trace")));
    records.push_back(std::move(r));
  }
  if (records.size() != pairings) {
    throw std::invalid_argument(fmt::format("{} games, expected {} (one per pairing)", records.size(), pairings));
  }
  return records;
}

}  // namespace

MatchupExperiment::MatchupExperiment(std::shared_ptr<const world::Arena> arena, TrialConfig base, MatchupSettings settings)
    : arena_(std::move(arena)),
      base_(std::move(base)),
      settings_(std::move(settings)),
      sims_(make_matchup_sims(arena_, base_.game, settings_)) {
  if (!settings_.pool) settings_.pool = std::make_shared<const OpponentPool>(make_pool(arena_, base_.game, base_.training));
  // A saved network reads what its agents observe in every pairing it plays: refused before any run when not.
  for (std::size_t p = 0; p < settings_.pursuers.size(); ++p) {
    for (std::size_t e = 0; e < settings_.evaders.size(); ++e) {
      const game::Sim& sim = sims_[1 + p * settings_.evaders.size() + e];
      if (settings_.pursuers[p] == players::kFacl && settings_.pursuer_policy) {
        settings_.pursuer_policy->check_fits(sim, game::Role::kPursuer);
      }
      if (settings_.evaders[e] == players::kFacl && settings_.evader_policy) {
        settings_.evader_policy->check_fits(sim, game::Role::kEvader);
      }
    }
  }
}

MatchupExperiment::~MatchupExperiment() = default;

std::size_t MatchupExperiment::episodes_per_run() const {
  return static_cast<std::size_t>(settings_.sweep.episodes) + 1 + pairings();
}

void MatchupExperiment::begin(const sweep::SweepControl& control) {
  settings_.sweep.control = control;
  play_ = std::make_unique<const MatchupRun>(sims_, settings_, base_.training);
  per_run_.assign(run_count(), {});
}

void MatchupExperiment::run_one(std::size_t i) {
  per_run_[i] = play_->play(i);
  if (settings_.sweep.control.progress) settings_.sweep.control.progress->run_done();
}

nlohmann::json MatchupExperiment::encode(std::size_t i) const { return encode_games(per_run_[i]); }

void MatchupExperiment::restore(std::size_t i, const nlohmann::json& record) {
  per_run_[i] = restore_games(record, pairings());
}

void MatchupExperiment::finish(bool root) {
  if (!root) return;
  records_.clear();
  for (auto& v : per_run_) std::move(v.begin(), v.end(), std::back_inserter(records_));
  per_run_.clear();
  summary_ = summarize_matchups(records_, settings_);
}

void MatchupExperiment::write_results(const std::filesystem::path& out, const SweepTiming&) const {
  write_matchups_csv(out / "matchups.csv", records_);
  write_matchup_agents_csv(out / "agents.csv", records_);
  results::write_json(out / "summary.json", summary_);
}

nlohmann::ordered_json MatchupExperiment::run_info() const {
  return {{"setup", setup()}, {"seeds", matchup_seeds(*arena_, settings_)}};
}

std::vector<RecordedEpisode> MatchupExperiment::recorded() const {
  std::vector<RecordedEpisode> out;
  for (std::size_t k = 0; k < records_.size(); ++k) {
    const MatchupRecord& r = records_[k];
    if (!r.trace) continue;
    // Each run's games are its pairings in order, so game k is pairing k % pairings (Sim 1 + that).
    out.push_back({matchup_key(r), &sims_[1 + k % pairings()], r.trace.get(),
                   fmt::format("{} {} repeat {}: {} vs {}", arena_->map().name, r.scenario, r.repeat, r.pursuer, r.evader),
                   fmt::format("peg-matchup, seed {}; {}", settings_.sweep.seed, ending_of(r.result))});
  }
  return out;
}

std::string MatchupExperiment::report(const SweepTiming&) const { return matchup_table(summary_); }

std::string matchup_key(const MatchupRecord& r) {
  return fmt::format("{}_r{}_{}_vs_{}", r.scenario, r.repeat, r.pursuer, r.evader);
}

void write_matchups_csv(const std::filesystem::path& file, const std::vector<MatchupRecord>& records) {
  AtomicFile out(file);
  results::CsvWriter csv(out.stream(), results::with_episode_columns({"scenario", "repeat", "pursuer", "evader"}));
  for (const MatchupRecord& r : records) {
    auto row = csv.row();
    row.add(r.scenario).add(r.repeat).add(r.pursuer).add(r.evader);
    results::add_episode_cells(row, r.result);
    row.end();
  }
  out.commit();
}

void write_matchup_agents_csv(const std::filesystem::path& file, const std::vector<MatchupRecord>& records) {
  AtomicFile out(file);
  results::CsvWriter csv(out.stream(), {"scenario", "repeat", "pursuer", "evader", "role", "rank", "path_m", "return",
                               "pinned_fraction", "collisions", "captures", "captured", "capture_time_s"});
  for (const MatchupRecord& r : records) {
    for (const game::AgentSummary& a : r.agents) {
      const bool captured = a.captured_at >= 0.0;
      csv.row()
          .add(r.scenario)
          .add(r.repeat)
          .add(r.pursuer)
          .add(r.evader)
          .add(game::to_string(a.role))
          .add(a.rank)
          .add(a.path)
          .add(a.total_reward)
          .add(a.pinned_fraction)
          .add(a.collisions)
          .add(a.captures)
          .add(static_cast<int>(captured))
          .add(captured ? a.captured_at : std::numeric_limits<double>::quiet_NaN())
          .end();
    }
  }
  out.commit();
}

nlohmann::ordered_json summarize_matchups(const std::vector<MatchupRecord>& records, const MatchupSettings& s) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  const auto rate_json = [&](const results::ProportionInterval& r) {
    return nlohmann::ordered_json{{"rate", num(r.rate)}, {"lo", r.lo}, {"hi", r.hi}};
  };
  for (const auto& p : s.pursuers) {
    for (const auto& e : s.evaders) {
      const std::string pname = matchup_policy_name(s, game::Role::kPursuer, p);
      const std::string ename = matchup_policy_name(s, game::Role::kEvader, e);
      std::size_t runs = 0, caps = 0, coll = 0, evaders = 0, evaders_captured = 0;
      std::vector<double> time, each, path, epath, pinned;
      for (const auto& r : records) {
        if (r.pursuer != pname || r.evader != ename) continue;
        ++runs;
        caps += r.result.captured();
        coll += r.result.collisions > 0;
        evaders += static_cast<std::size_t>(r.result.evaders);
        evaders_captured += static_cast<std::size_t>(r.result.captures);
        if (r.result.captured()) time.push_back(r.result.duration);
        for (const auto& a : r.agents)
          if (a.captured_at >= 0.0) each.push_back(a.captured_at);
        path.push_back(r.result.pursuer_path);
        epath.push_back(r.result.evader_path);
        pinned.push_back(r.result.pinned_fraction(game::Role::kEvader));
      }
      out.push_back({{"pursuer", pname},
                     {"evader", ename},
                     {"runs", runs},
                     {"captures", caps},
                     {"capture_rate", rate_json(results::wilson_interval(caps, runs))},
                     {"capture_time_s", num(results::mean_interval(time).mean)},
                     {"evaders", evaders},
                     {"evaders_captured", evaders_captured},
                     {"evader_capture_rate", rate_json(results::wilson_interval(evaders_captured, evaders))},
                     {"time_to_each_capture_s", num(results::mean_interval(each).mean)},
                     {"pursuer_path_m", num(results::mean_interval(path).mean)},
                     {"evader_path_m", num(results::mean_interval(epath).mean)},
                     {"collision_runs", coll},
                     {"evader_pinned_fraction", num(results::mean_interval(pinned).mean)}});
    }
  }
  return out;
}

std::string matchup_table(const nlohmann::ordered_json& summary) {
  const auto num = [](const nlohmann::ordered_json& j) { return j.is_number() ? j.get<double>() : std::nan(""); };
  std::string s = fmt::format("{:<14} {:<16} {:>9} {:>20} {:>13} {:>11} {:>12} {:>12} {:>6} {:>8}\n", "pursuer",
                              "evader", "all caught", "rate [95% CI]", "evaders", "each t (s)", "last t (s)",
                              "P path (m)", "coll.", "E pinned");
  for (const auto& r : summary) {
    s += fmt::format("{:<14} {:<16} {:>4}/{:<4} {:>20} {:>6}/{:<6} {:>11.1f} {:>12.1f} {:>12.1f} {:>6} {:>8.3f}\n",
                     r["pursuer"].get<std::string>(), r["evader"].get<std::string>(), r["captures"].get<int>(),
                     r["runs"].get<int>(),
                     fmt::format("{:.2f} [{:.2f}, {:.2f}]", num(r["capture_rate"]["rate"]), num(r["capture_rate"]["lo"]),
                                 num(r["capture_rate"]["hi"])),
                     r["evaders_captured"].get<int>(), r["evaders"].get<int>(), num(r["time_to_each_capture_s"]),
                     num(r["capture_time_s"]), num(r["pursuer_path_m"]), r["collision_runs"].get<int>(),
                     num(r["evader_pinned_fraction"]));
  }
  return s;
}

}  // namespace peg3d::experiment
