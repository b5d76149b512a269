#include "experiment/generalize_experiment.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/config_json.hpp"
#include "core/random.hpp"
#include "experiment/trial.hpp"
#include "players/policy_io.hpp"
#include "results/codecs.hpp"
#include "results/csv_writer.hpp"
#include "results/result_files.hpp"
#include "results/run_info.hpp"
#include "results/statistics.hpp"
#include "sweep/progress_reporter.hpp"
#include "sweep/sweep_driver.hpp"

namespace peg3d::experiment {

std::vector<std::string> eval_map_names(const std::vector<std::shared_ptr<const world::Arena>>& arenas) {
  std::vector<std::string> names;
  for (const auto& a : arenas) {
    std::string name = a->map().name.empty() ? a->map().source.stem().string() : a->map().name;
    if (name.empty()) name = "map";
    std::string unique = name;
    for (int k = 2; std::find(names.begin(), names.end(), unique) != names.end(); ++k) unique = fmt::format("{}-{}", name, k);
    names.push_back(unique);
  }
  return names;
}

std::size_t generalize_run_count(const game::Sim& train, const GeneralizeSettings& s) {
  return train.arena().map().scenarios.size() * static_cast<std::size_t>(s.sweep.repeats);
}

nlohmann::json generalize_setup(const game::Sim& train, const TrialConfig& config, const std::vector<EvalMap>& evals,
                                const GeneralizeSettings& s) {
  nlohmann::json maps = nlohmann::json::array();
  for (const EvalMap& m : evals) maps.push_back({{"name", m.name}, {"map_hash", results::map_content_hash(m.sim.arena())}});
  nlohmann::json setup = setup_header("generalize", train.arena(), s.sweep);
  setup["eval_maps"] = std::move(maps);
  setup["repeats"] = s.sweep.repeats;
  setup["config"] = config::to_json(config);
  return setup;
}

nlohmann::ordered_json generalize_seeds(const game::Sim& train, const GeneralizeSettings& s) {
  return {{"root", s.sweep.seed},
          {"derivation", "run seed = derive_seed(root, {scenario index, repeat}); training as a trial with the run "
                         "seed; evaluation on map m, scenario k = derive_seed(run seed, {20, m, k})"},
          {"runs", scenario_run_seeds(train.arena().map().scenarios, s.sweep.repeats, s.sweep.seed)}};
}

std::string generalize_key(const GeneralizeRecord& r) {
  return fmt::format("{}_r{}_on_{}_{}", r.train_scenario, r.repeat, r.eval_map, r.eval_scenario);
}

namespace {

// The frozen models of one training run on every scenario of every evaluation map, one greedy game each.
std::vector<GeneralizeRecord> evaluate_everywhere(const TrialResult& t, const std::string& train_scenario, int rep,
                                                  std::uint64_t seed, const std::vector<EvalMap>& evals,
                                                  const GeneralizeSettings& s) {
  std::vector<GeneralizeRecord> records;
  for (std::size_t m = 0; m < evals.size(); ++m) {
    const game::Sim& sim = evals[m].sim;
    game::SimState state(sim);
    const auto& eval_scenarios = sim.arena().map().scenarios;
    for (std::size_t k = 0; k < eval_scenarios.size(); ++k) {
      sweep::throw_if_stopped(s.sweep.control.stop);
      const world::Scenario& es = eval_scenarios[k];
      players::Lineup lineup;
      players::add_frozen(lineup, t.pursuer_models, static_cast<int>(es.pursuers.size()));
      players::add_frozen(lineup, t.evader_models, static_cast<int>(es.evaders.size()));
      GeneralizeRecord r{train_scenario, rep, evals[m].name, es.name, {}, {}};
      std::shared_ptr<game::Trace> trace;
      if (s.keep_trace && s.keep_trace(generalize_key(r))) {
        trace = std::make_shared<game::Trace>();
        trace->reserve(sim.max_steps(), es.agents());
      }
      r.result = evaluate(sim, state, es, lineup, derive_seed(seed, {20, m, k}), trace.get());
      r.trace = std::move(trace);
      records.push_back(std::move(r));
      if (s.sweep.control.progress) s.sweep.control.progress->episode_done();
    }
  }
  return records;
}

// A run's games and, for repeat 0, the trained models (saved as policies).
nlohmann::json encode_run(const std::vector<GeneralizeRecord>& records, const TrialResult* kept) {
  nlohmann::json games = nlohmann::json::array();
  for (const GeneralizeRecord& r : records) {
    games.push_back({{"train_scenario", r.train_scenario},
                     {"repeat", r.repeat},
                     {"eval_map", r.eval_map},
                     {"eval_scenario", r.eval_scenario},
                     {"result", results::episode_to_json(r.result)}});
    if (r.trace) games.back()["trace"] = results::trace_to_json(*r.trace);
  }
  nlohmann::json data{{"games", std::move(games)}};
  if (kept) {
    data["pursuer_models"] = results::role_models_to_json(kept->pursuer_models);
    data["evader_models"] = results::role_models_to_json(kept->evader_models);
  }
  return data;
}

std::vector<GeneralizeRecord> restore_run(const nlohmann::json& data, TrialResult* kept) {
  std::vector<GeneralizeRecord> records;
  for (const auto& g : data.at("games")) {
    records.push_back({g.at("train_scenario").get<std::string>(), g.at("repeat").get<int>(),
                       g.at("eval_map").get<std::string>(), g.at("eval_scenario").get<std::string>(),
                       results::episode_from_json(g.at("result")), {}});
    if (g.contains("trace")) records.back().trace = std::make_shared<const game::Trace>(results::trace_from_json(g.at("trace")));
  }
  if (kept) {
    kept->pursuer_models = results::role_models_from_json(data.at("pursuer_models"), game::Role::kPursuer);
    kept->evader_models = results::role_models_from_json(data.at("evader_models"), game::Role::kEvader);
  }
  return records;
}

}  // namespace

namespace {

std::vector<EvalMap> make_eval_maps(const std::vector<std::shared_ptr<const world::Arena>>& arenas,
                                    const game::GameConfig& config) {
  const std::vector<std::string> names = eval_map_names(arenas);
  std::vector<EvalMap> evals;
  for (std::size_t m = 0; m < arenas.size(); ++m) evals.push_back({names[m], game::Sim(arenas[m], config)});
  return evals;
}

}  // namespace

GeneralizeExperiment::GeneralizeExperiment(std::shared_ptr<const world::Arena> train,
                                           std::vector<std::shared_ptr<const world::Arena>> evals,
                                           const TrialConfig& config, GeneralizeSettings settings)
    : config_(config), train_(train, config.game), evals_(make_eval_maps(evals, config.game)), settings_(std::move(settings)) {
  if (!settings_.pool) settings_.pool = std::make_shared<const OpponentPool>(make_pool(train, config.game, config.training));
}

std::size_t GeneralizeExperiment::episodes_per_run() const {
  std::size_t games = 0;
  for (const auto& e : evals_) games += e.sim.arena().map().scenarios.size();
  return static_cast<std::size_t>(settings_.sweep.episodes) + 1 + games;
}

std::optional<std::size_t> GeneralizeExperiment::kept_slot(std::size_t i) const {
  const std::size_t repeats = static_cast<std::size_t>(settings_.sweep.repeats);
  return i % repeats == 0 ? std::optional<std::size_t>(i / repeats) : std::nullopt;
}

void GeneralizeExperiment::begin(const sweep::SweepControl& control) {
  settings_.sweep.control = control;
  per_run_.assign(run_count(), {});
  kept_.assign(train_.arena().map().scenarios.size(), TrialResult{});
}

void GeneralizeExperiment::run_one(std::size_t i) {
  const auto& scenarios = train_.arena().map().scenarios;
  const sweep::SweepControl& control = settings_.sweep.control;
  const int sc = static_cast<int>(i / settings_.sweep.repeats), rep = static_cast<int>(i % settings_.sweep.repeats);
  const std::uint64_t seed = run_seed(settings_.sweep.seed, sc, rep);
  TrialResult t = run_trial(train_, {.scenario = &scenarios[std::size_t(sc)],
                                     .seed = seed,
                                     .episodes = settings_.sweep.episodes,
                                     .stop = control.stop,
                                     .training = config_.training,
                                     .pool = settings_.pool.get(),
                                     .progress = control.progress});
  per_run_[i] = evaluate_everywhere(t, scenarios[std::size_t(sc)].name, rep, seed, evals_, settings_);
  if (const auto slot = kept_slot(i)) kept_[*slot] = std::move(t);
  if (control.progress) control.progress->run_done();
}

nlohmann::json GeneralizeExperiment::encode(std::size_t i) const {
  const auto slot = kept_slot(i);
  return encode_run(per_run_[i], slot ? &kept_[*slot] : nullptr);
}

void GeneralizeExperiment::restore(std::size_t i, const nlohmann::json& record) {
  const auto slot = kept_slot(i);
  per_run_[i] = restore_run(record, slot ? &kept_[*slot] : nullptr);
}

void GeneralizeExperiment::finish(bool root) {
  if (!root) return;
  records_.clear();
  for (auto& v : per_run_) std::move(v.begin(), v.end(), std::back_inserter(records_));
  per_run_.clear();
  std::vector<std::string> names;
  for (const auto& e : evals_) names.push_back(e.name);
  summary_ = summarize_generalization(records_, names);
}

void GeneralizeExperiment::write_results(const std::filesystem::path& out, const SweepTiming&) const {
  const auto& scenarios = train_.arena().map().scenarios;
  std::filesystem::create_directories(out / "policies");
  for (std::size_t sc = 0; sc < scenarios.size(); ++sc) {
    for (const auto& [role, models] :
         {std::pair{"pursuer", &kept_[sc].pursuer_models}, std::pair{"evader", &kept_[sc].evader_models}}) {
      for (std::size_t m = 0; m < models->models.size(); ++m) {
        const std::string key = scenarios[sc].name + "_" + role + (m == 0 ? std::string() : std::to_string(m));
        players::save_policy(results::output_file(out / "policies", key, ".json"), *models->models[m]);
      }
    }
  }
  write_generalization_csv(out / "generalization.csv", records_);
  results::write_json(out / "summary.json", summary_);
}

std::vector<std::pair<std::string, const world::Arena*>> GeneralizeExperiment::maps() const {
  std::vector<std::pair<std::string, const world::Arena*>> maps{{"train", &train_.arena()}};
  for (const auto& e : evals_) maps.emplace_back("eval " + e.name, &e.sim.arena());
  return maps;
}

nlohmann::ordered_json GeneralizeExperiment::run_info() const {
  return {{"setup", setup()}, {"seeds", generalize_seeds(train_, settings_)}};
}

std::vector<RecordedEpisode> GeneralizeExperiment::recorded() const {
  std::vector<RecordedEpisode> out;
  for (const EvalMap& e : evals_) {
    for (const auto& r : records_) {
      if (!r.trace || r.eval_map != e.name) continue;
      out.push_back({generalize_key(r), &e.sim, r.trace.get(),
                     fmt::format("trained on {} {} (repeat {}), played on {} {}", train_.arena().map().name,
                                 r.train_scenario, r.repeat, r.eval_map, r.eval_scenario),
                     fmt::format("peg-generalize, seed {}, {} training episodes; {}", settings_.sweep.seed,
                                 settings_.sweep.episodes, ending_of(r.result))});
    }
  }
  return out;
}

std::string GeneralizeExperiment::report(const SweepTiming&) const {
  return fmt::format("trained on {} ({} scenarios x {} repeats, {} episodes each)\n", train_.arena().map().source.string(),
                     train_.arena().map().scenarios.size(), settings_.sweep.repeats, settings_.sweep.episodes) +
         generalization_table(summary_);
}

void write_generalization_csv(const std::filesystem::path& file, const std::vector<GeneralizeRecord>& records) {
  AtomicFile out(file);
  results::CsvWriter csv(out.stream(), results::with_episode_columns({"train_scenario", "repeat", "eval_map", "eval_scenario"}));
  for (const GeneralizeRecord& r : records) {
    auto row = csv.row();
    row.add(r.train_scenario).add(r.repeat).add(r.eval_map).add(r.eval_scenario);
    results::add_episode_cells(row, r.result);
    row.end();
  }
  out.commit();
}

nlohmann::ordered_json summarize_generalization(const std::vector<GeneralizeRecord>& records,
                                                const std::vector<std::string>& maps) {
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const std::string& m : maps) {
    std::size_t runs = 0, caps = 0, coll = 0;
    std::vector<double> time;
    for (const auto& r : records) {
      if (r.eval_map != m) continue;
      ++runs;
      caps += r.result.captured();
      coll += r.result.collisions > 0;
      if (r.result.captured()) time.push_back(r.result.duration);
    }
    const results::ProportionInterval cr = results::wilson_interval(caps, runs), kr = results::wilson_interval(coll, runs);
    out.push_back({{"map", m},
                   {"runs", runs},
                   {"captures", caps},
                   {"capture_rate", {{"rate", num(cr.rate)}, {"lo", cr.lo}, {"hi", cr.hi}}},
                   {"collision_runs", coll},
                   {"collision_rate", {{"rate", num(kr.rate)}, {"lo", kr.lo}, {"hi", kr.hi}}},
                   {"capture_time_s", num(results::mean_interval(time).mean)}});
  }
  return out;
}

std::string generalization_table(const nlohmann::ordered_json& summary) {
  const auto num = [](const nlohmann::ordered_json& j) { return j.is_number() ? j.get<double>() : std::nan(""); };
  std::string s = fmt::format("{:<16} {:>9} {:>20} {:>20} {:>14}\n", "evaluation map", "captures", "capture rate [95%]",
                              "collision rate [95%]", "capture t (s)");
  for (const auto& r : summary) {
    s += fmt::format("{:<16} {:>4}/{:<4} {:>20} {:>20} {:>14.1f}\n", r["map"].get<std::string>(),
                     r["captures"].get<int>(), r["runs"].get<int>(),
                     fmt::format("{:.2f} [{:.2f}, {:.2f}]", num(r["capture_rate"]["rate"]), num(r["capture_rate"]["lo"]),
                                 num(r["capture_rate"]["hi"])),
                     fmt::format("{:.2f} [{:.2f}, {:.2f}]", num(r["collision_rate"]["rate"]),
                                 num(r["collision_rate"]["lo"]), num(r["collision_rate"]["hi"])),
                     num(r["capture_time_s"]));
  }
  return s;
}

}  // namespace peg3d::experiment
