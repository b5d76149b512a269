#include "experiment/matchup_experiment.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/random.hpp"
#include "experiment/atomic_file.hpp"
#include "experiment/csv_writer.hpp"
#include "experiment/paper_experiment.hpp"
#include "experiment/parallel_runner.hpp"
#include "experiment/progress_reporter.hpp"
#include "experiment/result_files.hpp"
#include "experiment/statistics.hpp"
#include "experiment/trial.hpp"
#include "game/facl_policy.hpp"

namespace peg3d::experiment {

game::AgentConfig scripted_agent(const game::AgentConfig& base, const std::string& policy) {
  game::AgentConfig a = base;
  a.policy = policy;
  a.motion_space = false;
  return a;
}

std::vector<MatchupRecord> run_matchups(std::shared_ptr<const world::Arena> arena, const game::GameConfig& config,
                                        const MatchupSettings& s, ProgressReporter* progress) {
  const auto& scenarios = arena->map().scenarios;
  const std::size_t n_p = s.pursuers.size(), n_e = s.evaders.size();
  const std::size_t jobs = scenarios.size() * static_cast<std::size_t>(s.repeats);
  std::vector<std::vector<MatchupRecord>> per_job(jobs);
  const bool need_facl = [&] {
    for (const auto& p : s.pursuers) if (p == "facl" && !s.pursuer_policy) return true;
    for (const auto& e : s.evaders) if (e == "facl" && !s.evader_policy) return true;
    return false;
  }();
  run_indexed(jobs, s.threads, [&](std::size_t i) {
    const int sc = static_cast<int>(i / s.repeats), rep = static_cast<int>(i % s.repeats);
    const std::uint64_t seed = run_seed(s.seed, sc, rep);
    std::unique_ptr<game::Policy> facl_pursuer, facl_evader;
    if (need_facl) {
      TrialSpec spec{&scenarios[sc], config, seed, s.episodes, false};
      TrialResult t = run_trial(arena, spec, progress);
      facl_pursuer = std::move(t.pursuer);
      facl_evader = std::move(t.evader);
    }
    if (s.pursuer_policy) facl_pursuer = load_policy(*s.pursuer_policy);
    if (s.evader_policy) facl_evader = load_policy(*s.evader_policy);
    for (std::size_t p = 0; p < n_p; ++p) {
      for (std::size_t e = 0; e < n_e; ++e) {
        game::GameConfig c = config;
        const std::uint64_t pseed = derive_seed(seed, {10, p, e});
        std::unique_ptr<game::Policy> pursuer, evader;
        game::Policy* pp = facl_pursuer.get();
        game::Policy* ep = facl_evader.get();
        if (s.pursuers[p] != "facl") {
          c.pursuer = scripted_agent(config.pursuer, s.pursuers[p]);
          pursuer = game::make_policy(c.pursuer, game::Role::kPursuer, pseed);
          pp = pursuer.get();
        } else if (s.pursuer_policy) {
          c.pursuer = static_cast<const game::FaclPolicy*>(pp)->config();
        }
        if (s.evaders[e] != "facl") {
          c.evader = scripted_agent(config.evader, s.evaders[e]);
          evader = game::make_policy(c.evader, game::Role::kEvader, derive_seed(pseed, {1}));
          ep = evader.get();
        } else if (s.evader_policy) {
          c.evader = static_cast<const game::FaclPolicy*>(ep)->config();
        }
        per_job[i].push_back({scenarios[sc].name, rep, s.pursuers[p], s.evaders[e],
                              evaluate(arena, c, scenarios[sc], *pp, *ep, derive_seed(pseed, {2}))});
        if (progress) progress->episode_done();
      }
    }
    if (progress) progress->run_done();
  });
  std::vector<MatchupRecord> out;
  for (auto& v : per_job) std::move(v.begin(), v.end(), std::back_inserter(out));
  return out;
}

void write_matchups_csv(const std::filesystem::path& file, const std::vector<MatchupRecord>& records) {
  AtomicFile out(file);
  CsvWriter csv(out.stream(), with_episode_columns({"scenario", "repeat", "pursuer", "evader"}));
  for (const MatchupRecord& r : records) {
    auto row = csv.row();
    row.add(r.scenario).add(r.repeat).add(r.pursuer).add(r.evader);
    add_episode_cells(row, r.result);
    row.end();
  }
  out.commit();
}

nlohmann::ordered_json summarize_matchups(const std::vector<MatchupRecord>& records, const MatchupSettings& s) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  for (const auto& p : s.pursuers) {
    for (const auto& e : s.evaders) {
      std::size_t runs = 0, caps = 0, coll = 0;
      std::vector<double> time, path, pinned;
      for (const auto& r : records) {
        if (r.pursuer != p || r.evader != e) continue;
        ++runs;
        caps += r.result.captured();
        coll += r.result.collisions > 0;
        if (r.result.captured()) time.push_back(r.result.duration);
        path.push_back(r.result.pursuer_path);
        pinned.push_back(r.result.pinned_fraction(game::Role::kEvader));
      }
      const ProportionInterval rate = wilson_interval(caps, runs);
      out.push_back({{"pursuer", p},
                     {"evader", e},
                     {"runs", runs},
                     {"captures", caps},
                     {"capture_rate", {{"rate", num(rate.rate)}, {"lo", rate.lo}, {"hi", rate.hi}}},
                     {"capture_time_s", num(mean_interval(time).mean)},
                     {"pursuer_path_m", num(mean_interval(path).mean)},
                     {"collision_runs", coll},
                     {"evader_pinned_fraction", num(mean_interval(pinned).mean)}});
    }
  }
  return out;
}

std::string matchup_table(const nlohmann::ordered_json& summary) {
  const auto num = [](const nlohmann::ordered_json& j) { return j.is_number() ? j.get<double>() : std::nan(""); };
  std::string s = fmt::format("{:<14} {:<16} {:>9} {:>20} {:>15} {:>16} {:>6} {:>14}\n", "pursuer", "evader",
                              "captures", "rate [95% CI]", "capture t (s)", "pursuer path (m)", "coll.", "evader pinned");
  for (const auto& r : summary) {
    s += fmt::format("{:<14} {:<16} {:>4}/{:<4} {:>20} {:>15.1f} {:>16.1f} {:>6} {:>14.3f}\n", r["pursuer"].get<std::string>(),
                     r["evader"].get<std::string>(), r["captures"].get<int>(), r["runs"].get<int>(),
                     fmt::format("{:.2f} [{:.2f}, {:.2f}]", num(r["capture_rate"]["rate"]), num(r["capture_rate"]["lo"]),
                                 num(r["capture_rate"]["hi"])),
                     num(r["capture_time_s"]), num(r["pursuer_path_m"]), r["collision_runs"].get<int>(),
                     num(r["evader_pinned_fraction"]));
  }
  return s;
}

}  // namespace peg3d::experiment
