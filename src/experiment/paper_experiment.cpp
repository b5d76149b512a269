#include "experiment/paper_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/config_json.hpp"
#include "experiment/trial.hpp"
#include "players/policy_io.hpp"
#include "results/result_files.hpp"
#include "results/trajectory_file.hpp"
#include "results/codecs.hpp"
#include "results/run_info.hpp"
#include "results/statistics.hpp"
#include "sweep/progress_reporter.hpp"
#include "sweep/sweep_driver.hpp"

namespace peg3d::experiment {
namespace {

nlohmann::ordered_json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json interval_json(const results::MeanInterval& m) {
  return {{"mean", finite_or_null(m.mean)}, {"lo", finite_or_null(m.lo)}, {"hi", finite_or_null(m.hi)},
          {"stddev", finite_or_null(m.stddev)}, {"n", m.n}};
}

double num_or_nan(const nlohmann::ordered_json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

}  // namespace

std::size_t paper_run_count(const world::Arena& arena, const std::vector<Algorithm>& algorithms, const PaperSettings& s) {
  return arena.map().scenarios.size() * algorithms.size() * static_cast<std::size_t>(s.sweep.repeats);
}

nlohmann::json paper_setup(const world::Arena& arena, const std::vector<Algorithm>& algorithms, const PaperSettings& s) {
  nlohmann::json setup = setup_header("paper", arena, s.sweep);
  setup["repeats"] = s.sweep.repeats;
  setup["trace_repeat"] = s.trace_repeat;
  setup["algorithms"] = algorithms_json(algorithms);
  return setup;
}

nlohmann::ordered_json paper_run_info(const PaperSettings& s) {
  return {{"configuration", "config.json: every algorithm's effective configuration, the seed, episodes, repeats, map"},
          {"trace_repeat", s.trace_repeat},
          {"seeds", "root seed in config.json; each run's seed, derive_seed(root, {scenario index, repeat}), in the "
                    "seed column of runs.csv"}};
}

namespace {

// Where run i of the sweep sits: scenario-major, then algorithm, then repeat.
struct PaperRun {
  std::size_t scenario, algorithm, repeat;
};

PaperRun paper_run(std::size_t i, std::size_t algorithms, std::size_t repeats) {
  return {i / (algorithms * repeats), (i / repeats) % algorithms, i % repeats};
}

// What the result files need of a run: its evaluation, learning curve and, when traced, its steps and
// trained models.
nlohmann::json encode_trial(const TrialResult& t, bool traced) {
  nlohmann::json data{{"evaluation", results::episode_to_json(t.evaluation)},
                      {"training", results::episodes_to_json(t.training.episodes)},
                      {"training_opponent", t.training.opponents}};
  if (traced) {
    data["trace"] = results::trace_to_json(t.trace);
    data["pursuer_models"] = results::role_models_to_json(t.pursuer_models);
    data["evader_models"] = results::role_models_to_json(t.evader_models);
  }
  return data;
}

void restore_trial(TrialResult& t, const nlohmann::json& data, bool traced, const OpponentPool& pool) {
  t.evaluation = results::episode_from_json(data.at("evaluation"));
  t.training.episodes = results::episodes_from_json(data.at("training"));
  t.training.opponents = data.at("training_opponent").get<std::vector<int>>();
  check_journaled_opponents(pool, t.training.opponents, t.training.episodes.size());
  if (traced) {
    t.trace = results::trace_from_json(data.at("trace"));
    t.pursuer_models = results::role_models_from_json(data.at("pursuer_models"), game::Role::kPursuer);
    t.evader_models = results::role_models_from_json(data.at("evader_models"), game::Role::kEvader);
  }
}

// The sweep's results from its trials, in run order; the traced repeat's steps and models are moved out.
PaperResults gather(const std::vector<Algorithm>& algorithms, const std::vector<world::Scenario>& scenarios,
                    const std::vector<OpponentPool>& pools, const PaperSettings& s, std::vector<TrialResult>& trials) {
  const std::size_t n_alg = algorithms.size(), n_rep = static_cast<std::size_t>(s.sweep.repeats);
  PaperResults r;
  r.runs.reserve(trials.size());
  r.curves.reserve(trials.size());
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const PaperRun at = paper_run(i, n_alg, n_rep);
    TrialResult& t = trials[i];
    const int sc = static_cast<int>(at.scenario), rep = static_cast<int>(at.repeat);
    results::RunRecord rec{scenarios[at.scenario].name, algorithms[at.algorithm].name, rep,
                           run_seed(s.sweep.seed, sc, rep), t.evaluation, t.train_captures()};
    r.steps += t.evaluation.steps;
    for (const auto& e : t.training.episodes) r.steps += e.steps;
    if (rep == s.trace_repeat) {
      const std::string key = rec.scenario + "_" + rec.algorithm;
      r.traces[key] = std::move(t.trace);
      for (const auto& [role, models] : {std::pair{"pursuer", &t.pursuer_models}, std::pair{"evader", &t.evader_models}}) {
        for (std::size_t m = 0; m < models->models.size(); ++m) {
          r.policies[key + "_" + role + (m == 0 ? std::string() : std::to_string(m))] = models->models[m];
        }
      }
    }
    r.runs.push_back(std::move(rec));
    r.curves.push_back({std::move(t.training.episodes), pool_opponent_names(pools[at.algorithm], t.training.opponents)});
  }
  return r;
}

}  // namespace

PaperExperiment::PaperExperiment(std::shared_ptr<const world::Arena> arena, std::vector<Algorithm> algorithms,
                                 PaperSettings settings, std::string map_file)
    : arena_(std::move(arena)),
      algorithms_(std::move(algorithms)),
      settings_(std::move(settings)),
      map_file_(std::move(map_file)),
      sims_(make_sims(arena_, algorithms_)),
      pools_(make_pools(arena_, algorithms_)) {}

void PaperExperiment::begin(const sweep::SweepControl& control) {
  control_ = control;
  trials_.assign(run_count(), TrialResult{});
}

void PaperExperiment::run_one(std::size_t i) {
  const PaperRun at = paper_run(i, algorithms_.size(), static_cast<std::size_t>(settings_.sweep.repeats));
  const auto& scenarios = arena_->map().scenarios;
  TrialSpec spec{.scenario = &scenarios[at.scenario],
                 .seed = run_seed(settings_.sweep.seed, static_cast<int>(at.scenario), static_cast<int>(at.repeat)),
                 .episodes = settings_.sweep.episodes,
                 .keep_trace = traced(i),
                 .stop = control_.stop,
                 .training = algorithms_[at.algorithm].config.training,
                 .pool = &pools_[at.algorithm],
                 .progress = control_.progress};
  trials_[i] = run_trial(sims_[at.algorithm], spec);
  if (!spec.keep_trace) {  // only the traced repeat's models are kept
    trials_[i].pursuer_models = {};
    trials_[i].evader_models = {};
  }
  if (control_.progress) control_.progress->run_done();
}

nlohmann::json PaperExperiment::encode(std::size_t i) const { return encode_trial(trials_[i], traced(i)); }

void PaperExperiment::restore(std::size_t i, const nlohmann::json& record) {
  const PaperRun at = paper_run(i, algorithms_.size(), static_cast<std::size_t>(settings_.sweep.repeats));
  restore_trial(trials_[i], record, traced(i), pools_[at.algorithm]);
}

void PaperExperiment::finish(bool root) {
  if (!root) return;
  results_ = gather(algorithms_, arena_->map().scenarios, pools_, settings_, trials_);
  trials_.clear();
  std::vector<std::string> scenario_names, algorithm_names;
  for (const auto& s : arena_->map().scenarios) scenario_names.push_back(s.name);
  for (const auto& a : algorithms_) algorithm_names.push_back(a.name);
  summary_ = summarize(results_.runs, scenario_names, algorithm_names, algorithms_.front().config.game.time_limit);
}

void PaperExperiment::write_results(const std::filesystem::path& out, const SweepTiming& timing) const {
  nlohmann::ordered_json config{{"map", map_file_},
                                {"seed", settings_.sweep.seed},
                                {"episodes", settings_.sweep.episodes},
                                {"repeats", settings_.sweep.repeats},
                                {"algorithms", nlohmann::ordered_json::object()}};
  for (const auto& a : algorithms_) {
    config["algorithms"][a.name] = nlohmann::ordered_json::parse(config::to_json(a.config).dump());
  }
  std::filesystem::create_directories(out / "trajectories");
  std::filesystem::create_directories(out / "policies");
  results::write_json(out / "config.json", config);
  results::write_runs_csv(out / "runs.csv", results_.runs);
  results::write_learning_curves_csv(out / "learning_curves.csv", results_.runs, results_.curves);
  results::write_json(out / "summary.json", summary_);
  for (const auto& [key, trace] : results_.traces) {
    results::write_trajectory_csv(results::output_file(out / "trajectories", key, ".csv"), trace);
  }
  for (const auto& [key, model] : results_.policies) {
    players::save_policy(results::output_file(out / "policies", key, ".json"), *model);
  }
  results::write_json(out / "map.json", results::map_to_json(*arena_));
  results::write_json(out / "apollonius.json",
                      results::apollonius_to_json({10, 10, 10}, {-10, -10, 10}, 1.1, 1.0, {0.5, 1.0, 2.0}));
  results::write_json(out / "timing.json",
                      nlohmann::ordered_json{{"world_build_s", timing.build_seconds},
                                             {"runs_s", timing.run_seconds},
                                             {"runs", run_count()},
                                             {"steps", results_.steps},
                                             {"steps_per_second", results_.steps / timing.run_seconds},
                                             {"threads", timing.threads},
                                             {"ranks", timing.ranks},
                                             {"world_cache", arena_->stats().cache_status}});
}

std::vector<RecordedEpisode> PaperExperiment::recorded() const {
  std::vector<RecordedEpisode> out;
  for (const auto& sc : arena_->map().scenarios) {
    for (std::size_t a = 0; a < algorithms_.size(); ++a) {
      const std::string key = sc.name + "_" + algorithms_[a].name;
      const auto trace = results_.traces.find(key);
      if (trace == results_.traces.end()) continue;
      const game::EpisodeResult* result = nullptr;
      for (const auto& r : results_.runs) {
        if (r.scenario == sc.name && r.algorithm == algorithms_[a].name && r.repeat == settings_.trace_repeat) {
          result = &r.evaluation;
        }
      }
      out.push_back({key, &sims_[a], &trace->second,
                     fmt::format("{} {}: {}", arena_->map().name, sc.name, algorithms_[a].name),
                     fmt::format("peg-paper, seed {}, repeat {} after {} training episodes; {}", settings_.sweep.seed,
                                 settings_.trace_repeat, settings_.sweep.episodes,
                                 result ? ending_of(*result) : std::string("evaluation"))});
    }
  }
  return out;
}

std::string PaperExperiment::report(const SweepTiming& timing) const {
  return summary_table(summary_) + fmt::format("\n{} runs, {} steps in {:.1f} s ({:.0f} steps/s)", run_count(),
                                               results_.steps, timing.run_seconds,
                                               static_cast<double>(results_.steps) / timing.run_seconds);
}

namespace {

using Runs = std::vector<const results::RunRecord*>;

// One algorithm's runs of one scenario: counts, the capture rate and the means with their intervals.
nlohmann::ordered_json algorithm_summary(const Runs& rs) {
  std::size_t captures = 0, collision_runs = 0, clean = 0;
  std::vector<double> time, ppath, epath, dist, epin, ppin;
  for (const results::RunRecord* r : rs) {
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
  const results::ProportionInterval rate = results::wilson_interval(captures, rs.size());
  return {
      {"runs", rs.size()},
      {"captures", captures},
      {"collision_runs", collision_runs},
      {"clean_captures", clean},
      {"capture_rate", {{"rate", finite_or_null(rate.rate)}, {"lo", rate.lo}, {"hi", rate.hi}}},
      {"capture_time_s", interval_json(results::mean_interval(time))},
      {"pursuer_path_m", interval_json(results::mean_interval(ppath))},
      {"evader_path_m", interval_json(results::mean_interval(epath))},
      {"final_distance_m", interval_json(results::mean_interval(dist))},
      {"evader_pinned_fraction", interval_json(results::mean_interval(epin))},
      {"pursuer_pinned_fraction", interval_json(results::mean_interval(ppin))},
  };
}

// Algorithms a and b on the same repeats of one scenario, paired by repeat: a metric's t and Wilcoxon tests.
nlohmann::ordered_json paired_comparison(const std::string& name_a, const Runs& a, const std::string& name_b,
                                         const Runs& b, const char* metric, double time_limit) {
  const std::size_t n = std::min(a.size(), b.size());
  const auto value = [&](const results::RunRecord* r) {
    if (std::string_view(metric) == "pursuer_path_m") return r->evaluation.pursuer_path;
    return r->evaluation.captured() ? r->evaluation.duration : time_limit;  // censored at the limit
  };
  std::vector<double> va, vb;
  for (std::size_t j = 0; j < n; ++j) {
    va.push_back(value(a[j]));
    vb.push_back(value(b[j]));
  }
  const results::PairedTTest t = results::paired_t_test(va, vb);
  const results::WilcoxonTest w = results::wilcoxon_signed_rank(va, vb);
  return {{"a", name_a},
          {"b", name_b},
          {"metric", metric},
          {"n", n},
          {"mean_a", finite_or_null(results::mean_interval(va).mean)},
          {"mean_b", finite_or_null(results::mean_interval(vb).mean)},
          {"mean_difference", finite_or_null(t.mean_difference)},
          {"t_test_p", finite_or_null(t.p_two_sided)},
          {"wilcoxon_p", finite_or_null(w.p_two_sided)}};
}

}  // namespace

nlohmann::ordered_json summarize(const std::vector<results::RunRecord>& runs, const std::vector<std::string>& scenarios,
                                 const std::vector<std::string>& algorithms, double time_limit) {
  nlohmann::ordered_json out{{"time_limit_s", time_limit}, {"scenarios", nlohmann::ordered_json::object()}};
  for (const std::string& sc : scenarios) {
    nlohmann::ordered_json& js = out["scenarios"][sc];
    js["algorithms"] = nlohmann::ordered_json::object();
    // Per algorithm, the runs ordered by repeat so that index k pairs across algorithms.
    std::map<std::string, Runs> by_alg;
    for (const results::RunRecord& r : runs)
      if (r.scenario == sc) by_alg[r.algorithm].push_back(&r);
    for (const std::string& alg : algorithms) {
      auto& rs = by_alg[alg];
      std::sort(rs.begin(), rs.end(), [](auto* a, auto* b) { return a->repeat < b->repeat; });
      js["algorithms"][alg] = algorithm_summary(rs);
    }
    js["comparisons"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < algorithms.size(); ++i) {
      for (std::size_t k = i + 1; k < algorithms.size(); ++k) {
        for (const char* metric : {"time_to_capture_s", "pursuer_path_m"}) {
          js["comparisons"].push_back(paired_comparison(algorithms[i], by_alg[algorithms[i]], algorithms[k],
                                                        by_alg[algorithms[k]], metric, time_limit));
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
