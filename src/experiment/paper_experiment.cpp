#include "experiment/paper_experiment.hpp"

#include <cmath>
#include <fstream>
#include <set>

#include <fmt/format.h>

#include "core/config_json.hpp"
#include "core/config_overrides.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/random.hpp"
#include "experiment/parallel_runner.hpp"
#include "experiment/progress_reporter.hpp"
#include "experiment/run_info.hpp"
#include "experiment/statistics.hpp"
#include "experiment/trial.hpp"

namespace peg3d::experiment {
namespace {

nlohmann::ordered_json interval_json(const MeanInterval& m) {
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  return {{"mean", num(m.mean)}, {"lo", num(m.lo)}, {"hi", num(m.hi)}, {"stddev", num(m.stddev)}, {"n", m.n}};
}

double num_or_nan(const nlohmann::ordered_json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

}  // namespace

game::GameConfig apply_game_overrides(game::GameConfig config, const std::vector<std::string>& overrides) {
  nlohmann::json j = config::to_json(config);
  config::apply_overrides(j, overrides);
  config::from_json(j, config);
  config.validate();
  return config;
}

game::GameConfig load_game_config(const std::string& source) {
  for (const char* name : game::kPresetNames)
    if (source == name) return game::preset(source);
  const std::filesystem::path file(source);
  if (file.extension() != ".json") {
    throw InputError(fmt::format("--config {}: neither a preset (peg3d, paper, baseline, robust) nor a .json file", source));
  }
  const std::string text = read_input_file(file, "configuration file");
  const nlohmann::json j = parse_json_text(text, file);
  game::GameConfig c = game::preset("peg3d");
  config::from_json(j, c, {file, false, text});
  try {
    c.validate();
  } catch (const InvalidParameter& e) {
    throw InputError(file, json_line_of(text, e.parameter()), e.parameter(), e.message());
  }
  return c;
}

std::vector<Algorithm> make_algorithms(const std::vector<std::string>& names, const std::vector<std::string>& overrides) {
  std::vector<Algorithm> out;
  std::set<std::string> seen;
  for (const std::string& n : names) {
    if (!seen.insert(n).second) throw InputError("algorithm '" + n + "' is listed twice");
    out.push_back({n, game::preset(n)});
  }
  std::vector<nlohmann::json> configs;
  for (const Algorithm& a : out) configs.push_back(config::to_json(a.config));
  for (const std::string& o : overrides) {
    const std::size_t dot = o.find('.'), eq = o.find('=');
    const std::string head = o.substr(0, std::min(dot, eq));
    bool targeted = false;
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (out[i].name == head && dot < eq) {
        config::apply_override(configs[i], std::string_view(o).substr(dot + 1));
        targeted = true;
      }
    }
    if (!targeted) {
      for (auto& c : configs) config::apply_override(c, o);
    }
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    config::from_json(configs[i], out[i].config);
    out[i].config.validate();
  }
  return out;
}

std::vector<game::Sim> make_sims(const std::shared_ptr<const world::Arena>& arena, const std::vector<Algorithm>& algorithms) {
  std::vector<game::Sim> sims;
  sims.reserve(algorithms.size());
  for (const Algorithm& a : algorithms) sims.emplace_back(arena, a.config);
  return sims;
}

std::vector<OpponentPool> make_pools(const std::shared_ptr<const world::Arena>& arena, const std::vector<Algorithm>& algorithms) {
  std::vector<OpponentPool> pools;
  pools.reserve(algorithms.size());
  for (const Algorithm& a : algorithms) pools.emplace_back(arena, a.config);
  return pools;
}

std::uint64_t run_seed(std::uint64_t root, int scenario, int repeat) {
  return derive_seed(root, {static_cast<std::uint64_t>(scenario), static_cast<std::uint64_t>(repeat)});
}

nlohmann::ordered_json scenario_run_seeds(const std::vector<world::Scenario>& scenarios, int repeats,
                                          std::uint64_t root) {
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (std::size_t sc = 0; sc < scenarios.size(); ++sc) {
    for (int rep = 0; rep < repeats; ++rep) {
      runs.push_back({{"run", sc * static_cast<std::size_t>(repeats) + static_cast<std::size_t>(rep)},
                      {"scenario", scenarios[sc].name},
                      {"repeat", rep},
                      {"seed", run_seed(root, static_cast<int>(sc), rep)}});
    }
  }
  return runs;
}

std::size_t paper_run_count(const world::Arena& arena, const std::vector<Algorithm>& algorithms, const SweepSettings& s) {
  return arena.map().scenarios.size() * algorithms.size() * static_cast<std::size_t>(s.repeats);
}

nlohmann::json paper_setup(const world::Arena& arena, const std::vector<Algorithm>& algorithms, const SweepSettings& s) {
  nlohmann::json algs = nlohmann::json::array();
  for (const Algorithm& a : algorithms) algs.push_back({{"name", a.name}, {"config", config::to_json(a.config)}});
  return {{"experiment", "paper"},         {"peg3d", peg3d_build_json()}, {"map_hash", map_content_hash(arena)},
          {"seed", s.seed},                {"episodes", s.episodes},      {"repeats", s.repeats},
          {"trace_repeat", s.trace_repeat}, {"algorithms", std::move(algs)}};
}

nlohmann::ordered_json paper_run_info(const SweepSettings& s) {
  return {{"configuration", "config.json: every algorithm's effective configuration, the seed, episodes, repeats, map"},
          {"trace_repeat", s.trace_repeat},
          {"seeds", "root seed in config.json; each run's seed, derive_seed(root, {scenario index, repeat}), in the "
                    "seed column of runs.csv"}};
}

PaperResults run_paper_experiment(const std::vector<Algorithm>& algorithms, const std::vector<game::Sim>& sims,
                                  const std::vector<OpponentPool>& pools, const SweepSettings& s,
                                  ProgressReporter* progress) {
  const auto& scenarios = sims.front().arena().map().scenarios;
  const std::size_t n_alg = algorithms.size(), n_rep = static_cast<std::size_t>(s.repeats);
  const std::size_t total = scenarios.size() * n_alg * n_rep;
  std::vector<TrialResult> trials(total);
  const auto traced = [&](std::size_t i) { return static_cast<int>(i % n_rep) == s.trace_repeat; };
  run_journaled(
      total, s.threads, s.control,
      [&](std::size_t i) {
        const std::size_t sc = i / (n_alg * n_rep), alg = (i / n_rep) % n_alg, rep = i % n_rep;
        TrialSpec spec;
        spec.scenario = &scenarios[sc];
        spec.seed = run_seed(s.seed, static_cast<int>(sc), static_cast<int>(rep));
        spec.episodes = s.episodes;
        spec.keep_trace = traced(i);
        spec.stop = s.control.stop;
        spec.pool = &pools[alg];
        trials[i] = run_trial(sims[alg], spec, progress);
        if (!spec.keep_trace) {  // only the traced repeat's models are kept
          trials[i].pursuer_models = {};
          trials[i].evader_models = {};
        }
        if (progress) progress->run_done();
      },
      // What the result files need of a run: its evaluation, learning curve and, when traced, its steps and
      // trained models.
      [&](std::size_t i) {
        const TrialResult& t = trials[i];
        nlohmann::json data{{"evaluation", episode_to_json(t.evaluation)},
                            {"training", episodes_to_json(t.training)},
                            {"training_opponent", t.training_opponent}};
        if (traced(i)) {
          data["trace"] = trace_to_json(t.trace);
          data["pursuer_models"] = role_models_to_json(t.pursuer_models);
          data["evader_models"] = role_models_to_json(t.evader_models);
        }
        return data;
      },
      [&](std::size_t i, const nlohmann::json& data) {
        TrialResult& t = trials[i];
        t.evaluation = episode_from_json(data.at("evaluation"));
        t.training = episodes_from_json(data.at("training"));
        t.training_opponent = data.at("training_opponent").get<std::vector<int>>();
        check_journaled_opponents(pools[(i / n_rep) % n_alg], t.training_opponent, t.training.size());
        if (traced(i)) {
          t.trace = trace_from_json(data.at("trace"));
          t.pursuer_models = role_models_from_json(data.at("pursuer_models"), game::Role::kPursuer);
          t.evader_models = role_models_from_json(data.at("evader_models"), game::Role::kEvader);
        }
      });

  PaperResults r;
  r.runs.reserve(total);
  r.curves.reserve(total);
  for (std::size_t i = 0; i < total; ++i) {
    const std::size_t sc = i / (n_alg * n_rep), alg = (i / n_rep) % n_alg, rep = i % n_rep;
    TrialResult& t = trials[i];
    RunRecord rec{scenarios[sc].name, algorithms[alg].name, static_cast<int>(rep),
                  run_seed(s.seed, static_cast<int>(sc), static_cast<int>(rep)), t.evaluation, t.train_captures()};
    r.steps += t.evaluation.steps;
    for (const auto& e : t.training) r.steps += e.steps;
    if (static_cast<int>(rep) == s.trace_repeat) {
      const std::string key = rec.scenario + "_" + rec.algorithm;
      r.traces[key] = std::move(t.trace);
      for (const auto& [role, models] : {std::pair{"pursuer", &t.pursuer_models}, std::pair{"evader", &t.evader_models}}) {
        for (std::size_t m = 0; m < models->models.size(); ++m) {
          r.policies[key + "_" + role + (m == 0 ? std::string() : std::to_string(m))] = models->models[m];
        }
      }
    }
    r.runs.push_back(std::move(rec));
    r.curves.push_back({std::move(t.training), pool_opponent_names(pools[alg], t.training_opponent)});
  }
  return r;
}

nlohmann::ordered_json summarize(const std::vector<RunRecord>& runs, const std::vector<std::string>& scenarios,
                         const std::vector<std::string>& algorithms, double time_limit) {
  nlohmann::ordered_json out{{"time_limit_s", time_limit}, {"scenarios", nlohmann::ordered_json::object()}};
  for (const std::string& sc : scenarios) {
    nlohmann::ordered_json& js = out["scenarios"][sc];
    js["algorithms"] = nlohmann::ordered_json::object();
    // Per algorithm, the runs ordered by repeat so that index k pairs across algorithms.
    std::map<std::string, std::vector<const RunRecord*>> by_alg;
    for (const RunRecord& r : runs)
      if (r.scenario == sc) by_alg[r.algorithm].push_back(&r);
    for (const std::string& alg : algorithms) {
      auto& rs = by_alg[alg];
      std::sort(rs.begin(), rs.end(), [](auto* a, auto* b) { return a->repeat < b->repeat; });
      std::size_t captures = 0, collision_runs = 0, clean = 0;
      std::vector<double> time, ppath, epath, dist, epin, ppin;
      for (const RunRecord* r : rs) {
        const auto& e = r->evaluation;
        captures += e.captured();
        collision_runs += e.collisions > 0;
        clean += e.captured() && e.collisions == 0;
        if (e.captured()) time.push_back(e.duration);
        ppath.push_back(e.pursuer_path);
        epath.push_back(e.evader_path);
        dist.push_back(e.final_distance);
        epin.push_back(e.pinned_fraction(game::Role::kEvader));
        ppin.push_back(e.pinned_fraction(game::Role::kPursuer));
      }
      const ProportionInterval rate = wilson_interval(captures, rs.size());
      js["algorithms"][alg] = {
          {"runs", rs.size()},
          {"captures", captures},
          {"collision_runs", collision_runs},
          {"clean_captures", clean},
          {"capture_rate",
           {{"rate", std::isfinite(rate.rate) ? nlohmann::ordered_json(rate.rate) : nlohmann::ordered_json(nullptr)},
            {"lo", rate.lo},
            {"hi", rate.hi}}},
          {"capture_time_s", interval_json(mean_interval(time))},
          {"pursuer_path_m", interval_json(mean_interval(ppath))},
          {"evader_path_m", interval_json(mean_interval(epath))},
          {"final_distance_m", interval_json(mean_interval(dist))},
          {"evader_pinned_fraction", interval_json(mean_interval(epin))},
          {"pursuer_pinned_fraction", interval_json(mean_interval(ppin))},
      };
    }
    js["comparisons"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < algorithms.size(); ++i) {
      for (std::size_t k = i + 1; k < algorithms.size(); ++k) {
        const auto& a = by_alg[algorithms[i]];
        const auto& b = by_alg[algorithms[k]];
        const std::size_t n = std::min(a.size(), b.size());
        for (const char* metric : {"time_to_capture_s", "pursuer_path_m"}) {
          std::vector<double> va, vb;
          for (std::size_t j = 0; j < n; ++j) {
            const auto value = [&](const RunRecord* r) {
              if (std::string_view(metric) == "pursuer_path_m") return r->evaluation.pursuer_path;
              return r->evaluation.captured() ? r->evaluation.duration : time_limit;  // censored at the limit
            };
            va.push_back(value(a[j]));
            vb.push_back(value(b[j]));
          }
          const PairedTTest t = paired_t_test(va, vb);
          const WilcoxonTest w = wilcoxon_signed_rank(va, vb);
          const auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
          js["comparisons"].push_back({{"a", algorithms[i]},
                                       {"b", algorithms[k]},
                                       {"metric", metric},
                                       {"n", n},
                                       {"mean_a", num(mean_interval(va).mean)},
                                       {"mean_b", num(mean_interval(vb).mean)},
                                       {"mean_difference", num(t.mean_difference)},
                                       {"t_test_p", num(t.p_two_sided)},
                                       {"wilcoxon_p", num(w.p_two_sided)}});
        }
      }
    }
  }
  return out;
}

std::string summary_table(const nlohmann::ordered_json& summary) {
  std::string s = fmt::format("{:<10} {:<10} {:>9} {:>19} {:>19} {:>19} {:>14} {:>6}\n", "scenario", "algorithm",
                              "captures", "rate [95% CI]", "capture time (s)", "pursuer path (m)", "evader pinned", "coll.");
  const auto mean_ci = [](const nlohmann::ordered_json& m) {
    const double mean = num_or_nan(m["mean"]), lo = num_or_nan(m["lo"]), hi = num_or_nan(m["hi"]);
    if (!std::isfinite(mean)) return std::string("-");
    return std::isfinite(lo) ? fmt::format("{:.1f} [{:.1f}, {:.1f}]", mean, lo, hi) : fmt::format("{:.1f}", mean);
  };
  for (const auto& [sc, js] : summary["scenarios"].items()) {
    for (const auto& [alg, a] : js["algorithms"].items()) {
      s += fmt::format("{:<10} {:<10} {:>4}/{:<4} {:>19} {:>19} {:>19} {:>14} {:>6}\n", sc, alg,
                       a["captures"].get<int>(), a["runs"].get<int>(),
                       fmt::format("{:.2f} [{:.2f}, {:.2f}]", num_or_nan(a["capture_rate"]["rate"]),
                                   a["capture_rate"]["lo"].get<double>(), a["capture_rate"]["hi"].get<double>()),
                       mean_ci(a["capture_time_s"]), mean_ci(a["pursuer_path_m"]),
                       fmt::format("{:.3f}", num_or_nan(a["evader_pinned_fraction"]["mean"])),
                       a["collision_runs"].get<int>());
    }
  }
  s += "\npaired comparisons (a - b; time censored at the limit):\n";
  for (const auto& [sc, js] : summary["scenarios"].items()) {
    for (const auto& c : js["comparisons"]) {
      s += fmt::format("  {:<6} {:>8} vs {:<8} {:<18} diff {:>8.2f}  t-test p {:<9.3g} Wilcoxon p {:.3g}\n", sc,
                       c["a"].get<std::string>(), c["b"].get<std::string>(), c["metric"].get<std::string>(),
                       num_or_nan(c["mean_difference"]), num_or_nan(c["t_test_p"]), num_or_nan(c["wilcoxon_p"]));
    }
  }
  return s;
}

}  // namespace peg3d::experiment
