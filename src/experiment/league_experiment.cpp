#include "experiment/league_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/config_json.hpp"
#include "core/random.hpp"
#include "core/validation.hpp"
#include "experiment/csv_writer.hpp"
#include "experiment/progress_reporter.hpp"
#include "experiment/result_files.hpp"
#include "experiment/run_info.hpp"
#include "experiment/statistics.hpp"
#include "experiment/trial.hpp"

namespace peg3d::experiment {
namespace {

bool facl_plays(const game::GameConfig& c, game::Role role) {
  return c.agent(role).policy == game::PolicyKind::kFacl;
}

int most_agents(const world::Arena& arena, game::Role role) {
  int n = 0;
  for (const auto& s : arena.map().scenarios)
    n = std::max(n, static_cast<int>(role == game::Role::kPursuer ? s.pursuers.size() : s.evaders.size()));
  return n;
}

/// Time each evader of the game stayed free, on average: its capture time, or the game's end.
double evader_survival(const game::EpisodeResult& r) {
  const int free = r.evaders - r.captures;
  return (r.capture_time_sum + free * r.duration) / std::max(1, r.evaders);
}

nlohmann::ordered_json num(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); }

/// The inverse of num(): a JSON number, or NaN for null.
double number_or_nan(const nlohmann::ordered_json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

nlohmann::ordered_json mean_json(const MeanInterval& m) {
  return {{"mean", num(m.mean)}, {"lo", num(m.lo)}, {"hi", num(m.hi)}, {"n", m.n}};
}

nlohmann::ordered_json rate_json(const ProportionInterval& r) { return {{"rate", num(r.rate)}, {"lo", r.lo}, {"hi", r.hi}}; }

}  // namespace

std::vector<Entrant> league_entrants(const std::vector<Algorithm>& algorithms, const LeagueSettings& s, game::Role role) {
  std::vector<Entrant> out;
  for (std::size_t a = 0; a < algorithms.size(); ++a) {
    if (!facl_plays(algorithms[a].config, role)) continue;
    for (int t = 0; t < s.train_seeds; ++t) {
      out.push_back({fmt::format("{}#{}", algorithms[a].name, t), algorithms[a].name, role, game::PolicyKind::kFacl,
                     static_cast<int>(a), t});
    }
  }
  for (const auto kind : role == game::Role::kPursuer ? s.classic_pursuers : s.classic_evaders) {
    out.push_back({game::to_string(kind), game::to_string(kind), role, kind, -1, -1});
  }
  return out;
}

League::League(std::shared_ptr<const world::Arena> train, std::vector<LeagueMap> eval_maps, std::vector<Algorithm> algorithms,
               LeagueSettings settings)
    : train_(std::move(train)), maps_(std::move(eval_maps)), algorithms_(std::move(algorithms)), settings_(std::move(settings)) {
  if (algorithms_.empty()) throw InvalidParameter("--algorithms", "(none)", "must name at least one algorithm");
  require_at_least("--train-seeds", settings_.train_seeds, 1);
  require_at_least("--eval-seeds", settings_.eval_seeds, 1);
  pursuers_ = league_entrants(algorithms_, settings_, game::Role::kPursuer);
  evaders_ = league_entrants(algorithms_, settings_, game::Role::kEvader);
  for (const Algorithm& a : algorithms_) {
    game::GameConfig training = a.config;
    if (settings_.train_heading) training.initial_heading = *settings_.train_heading;
    train_sims_.emplace_back(train_, training);
    pools_.emplace_back(train_, training);
  }
  // Groups: the algorithms, then the classic policies of the role.
  const int n_alg = static_cast<int>(algorithms_.size());
  pursuer_groups_ = n_alg + static_cast<int>(settings_.classic_pursuers.size());
  evader_groups_ = n_alg + static_cast<int>(settings_.classic_evaders.size());
  const game::GameConfig& rules = algorithms_.front().config;
  const auto side = [&](game::GameConfig& c, game::Role role, int group) {
    const auto& classic = role == game::Role::kPursuer ? settings_.classic_pursuers : settings_.classic_evaders;
    auto& all = role == game::Role::kPursuer ? c.pursuer : c.evader;
    auto& list = role == game::Role::kPursuer ? c.pursuers : c.evaders;
    if (group < n_alg) {
      const game::GameConfig& g = algorithms_[std::size_t(group)].config;
      all = role == game::Role::kPursuer ? g.pursuer : g.evader;
      list = role == game::Role::kPursuer ? g.pursuers : g.evaders;
      // Whom a team's agents play against is the team's strategy: its own algorithm's, not the rules'.
      if (role == game::Role::kPursuer) {
        c.team.pursuer_target = g.team.pursuer_target;
      } else {
        c.team.evader_threat = g.team.evader_threat;
      }
    } else {
      c = game::with_role_playing(std::move(c), role, classic[std::size_t(group - n_alg)]);
    }
  };
  for (const LeagueMap& m : maps_) {
    for (int p = 0; p < pursuer_groups_; ++p) {
      for (int e = 0; e < evader_groups_; ++e) {
        game::GameConfig c = rules;
        c.initial_heading = settings_.eval_heading;
        c.training = {};  // evaluation games do not train
        side(c, game::Role::kPursuer, p);
        side(c, game::Role::kEvader, e);
        eval_sims_.emplace_back(m.arena, std::move(c));
      }
    }
  }
  trained_pursuers_.resize(training_runs());
  trained_evaders_.resize(training_runs());
  training_.resize(training_runs());
  opponents_.resize(training_runs());
}

const game::Sim& League::sim_of(std::size_t map, int pursuer_group, int evader_group) const {
  return eval_sims_[(map * std::size_t(pursuer_groups_) + std::size_t(pursuer_group)) * std::size_t(evader_groups_) +
                    std::size_t(evader_group)];
}

std::size_t League::games() const {
  std::size_t starts = 0;
  for (const LeagueMap& m : maps_) starts += m.arena->map().scenarios.size();
  return starts * static_cast<std::size_t>(settings_.eval_seeds) * pursuers_.size() * evaders_.size();
}

nlohmann::json League::setup() const {
  nlohmann::json algs = nlohmann::json::array(), maps = nlohmann::json::array();
  for (const Algorithm& a : algorithms_) algs.push_back({{"name", a.name}, {"config", config::to_json(a.config)}});
  for (const LeagueMap& m : maps_) maps.push_back({{"name", m.name}, {"map_hash", map_content_hash(*m.arena)}});
  nlohmann::json pursuers = nlohmann::json::array(), evaders = nlohmann::json::array();
  for (const auto k : settings_.classic_pursuers) pursuers.push_back(game::to_string(k));
  for (const auto k : settings_.classic_evaders) evaders.push_back(game::to_string(k));
  return {{"experiment", "league"},
          {"peg3d", peg3d_build_json()},
          {"map_hash", map_content_hash(*train_)},
          {"eval_maps", std::move(maps)},
          {"seed", settings_.seed},
          {"episodes", settings_.episodes},
          {"train_seeds", settings_.train_seeds},
          {"eval_seeds", settings_.eval_seeds},
          {"eval_heading", config::enum_name(game::kInitialHeadingNames, settings_.eval_heading)},
          {"train_heading", settings_.train_heading
                                ? nlohmann::json(config::enum_name(game::kInitialHeadingNames, *settings_.train_heading))
                                : nlohmann::json("config")},
          {"classic_pursuers", std::move(pursuers)},
          {"classic_evaders", std::move(evaders)},
          {"algorithms", std::move(algs)}};
}

const game::RoleModels& League::models(int a, int t, game::Role role) const {
  const std::size_t run = std::size_t(a) * std::size_t(settings_.train_seeds) + std::size_t(t);
  return role == game::Role::kPursuer ? trained_pursuers_[run] : trained_evaders_[run];
}

LearningCurve League::curve(int a, int t) const {
  const std::size_t run = std::size_t(a) * std::size_t(settings_.train_seeds) + std::size_t(t);
  return {training_[run], pool_opponent_names(pools_[std::size_t(a)], opponents_[run])};
}

std::vector<League::Game> League::run(ProgressReporter* progress, bool root) const {
  const LeagueSettings& s = settings_;
  const auto& scenarios = train_->map().scenarios;
  const int max_p = most_agents(*train_, game::Role::kPursuer), max_e = most_agents(*train_, game::Role::kEvader);
  // 1. Training: run (a, t) is index a * train_seeds + t.
  run_journaled(
      training_runs(), s.threads, s.control,
      [&](std::size_t i) {
        const std::size_t a = i / std::size_t(s.train_seeds), t = i % std::size_t(s.train_seeds);
        const std::uint64_t seed = derive_seed(s.seed, {1, a, t});
        const game::Sim& sim = train_sims_[a];
        game::Lineup lineup;
        game::add_configured(lineup, sim.config(), game::Role::kPursuer, max_p, stream_seed(seed, TrialStream::kPursuer),
                             &trained_pursuers_[i]);
        game::add_configured(lineup, sim.config(), game::Role::kEvader, max_e, stream_seed(seed, TrialStream::kEvader),
                             &trained_evaders_[i]);
        game::SimState state(sim);
        train_lineup(sim, &pools_[a], lineup, max_p, scenarios, seed, s.episodes, s.control.stop, progress, state,
                     training_[i], opponents_[i]);
        if (progress) progress->run_done();
      },
      [&](std::size_t i) {
        return nlohmann::json{{"pursuers", role_models_to_json(trained_pursuers_[i])},
                              {"evaders", role_models_to_json(trained_evaders_[i])},
                              {"training", episodes_to_json(training_[i])},
                              {"training_opponent", opponents_[i]}};
      },
      [&](std::size_t i, const nlohmann::json& data) {
        trained_pursuers_[i] = role_models_from_json(data.at("pursuers"), game::Role::kPursuer);
        trained_evaders_[i] = role_models_from_json(data.at("evaders"), game::Role::kEvader);
        training_[i] = episodes_from_json(data.at("training"));
        opponents_[i] = data.at("training_opponent").get<std::vector<int>>();
        check_journaled_opponents(pools_[i / std::size_t(s.train_seeds)], opponents_[i], training_[i].size());
      });
  if (!root) return {};

  // 2. Evaluation on this process: one job per (map, scenario, evaluation seed) plays every pairing.
  struct Start {
    std::size_t map, scenario;
    int seed;
  };
  std::vector<Start> starts;
  for (std::size_t m = 0; m < maps_.size(); ++m)
    for (std::size_t sc = 0; sc < maps_[m].arena->map().scenarios.size(); ++sc)
      for (int k = 0; k < s.eval_seeds; ++k) starts.push_back({m, sc, k});
  const std::size_t pairings = pursuers_.size() * evaders_.size();
  std::vector<Game> games(starts.size() * pairings);
  const int n_alg = static_cast<int>(algorithms_.size());
  const auto group_of = [&](const Entrant& e, const std::vector<game::PolicyKind>& classic) {
    if (e.algorithm >= 0) return e.algorithm;
    return n_alg + static_cast<int>(std::find(classic.begin(), classic.end(), e.policy) - classic.begin());
  };
  // A stop during the games keeps the training runs (journaled): --resume reads them back and plays the games.
  const auto interrupted = [&] {
    const RunJournal* journal = s.control.journal;
    return SweepInterrupted(training_runs(), training_runs(), journal ? journal->file() : std::filesystem::path());
  };
  try {
    run_indexed(
        starts.size(), s.threads,
        [&](std::size_t j) {
          const Start& st = starts[j];
          const world::Scenario& scenario = maps_[st.map].arena->map().scenarios[st.scenario];
          const int np = static_cast<int>(scenario.pursuers.size()), ne = static_cast<int>(scenario.evaders.size());
          const std::uint64_t seed = derive_seed(s.seed, {2, st.map, st.scenario, static_cast<std::uint64_t>(st.seed)});
          game::SimState state(sim_of(st.map, 0, 0));
          for (std::size_t p = 0; p < pursuers_.size(); ++p) {
            for (std::size_t e = 0; e < evaders_.size(); ++e) {
              throw_if_stopped(s.control.stop);
              const Entrant& P = pursuers_[p];
              const Entrant& E = evaders_[e];
              const game::Sim& sim =
                  sim_of(st.map, group_of(P, s.classic_pursuers), group_of(E, s.classic_evaders));
              game::Lineup lineup;
              if (P.algorithm >= 0) {
                game::add_frozen(lineup, models(P.algorithm, P.train_seed, game::Role::kPursuer), np);
              } else {
                game::add_configured(lineup, sim.config(), game::Role::kPursuer, np, derive_seed(seed, {1}));
              }
              if (E.algorithm >= 0) {
                game::add_frozen(lineup, models(E.algorithm, E.train_seed, game::Role::kEvader), ne);
              } else {
                game::add_configured(lineup, sim.config(), game::Role::kEvader, ne, derive_seed(seed, {2}));
              }
              Game& g = games[j * pairings + p * evaders_.size() + e];
              g = {maps_[st.map].name, scenario.name, st.seed, P.name, E.name, evaluate(sim, state, scenario, lineup, seed)};
              if (progress) progress->episode_done();
            }
          }
        },
        s.control.stop);
  } catch (const RunCancelled&) {
    throw interrupted();
  }
  if (s.control.stop && s.control.stop()) throw interrupted();
  return games;
}

void write_league_learning_curves_csv(const std::filesystem::path& file, const League& league) {
  AtomicFile out(file);
  CsvWriter csv(out.stream(),
                with_episode_columns({"algorithm", "train_seed", "episode", "scenario", "pool_opponent"}));
  const auto& scenarios = league.train_arena().map().scenarios;
  for (std::size_t a = 0; a < league.algorithms().size(); ++a) {
    for (int t = 0; t < league.settings().train_seeds; ++t) {
      const LearningCurve c = league.curve(static_cast<int>(a), t);
      for (std::size_t e = 0; e < c.episodes.size(); ++e) {
        auto row = csv.row();
        row.add(league.algorithms()[a].name).add(t).add(e).add(scenarios[e % scenarios.size()].name).add(c.pool_opponents[e]);
        add_episode_cells(row, c.episodes[e]);
        row.end();
      }
    }
  }
  out.commit();
}

void write_league_games_csv(const std::filesystem::path& file, const std::vector<League::Game>& games) {
  AtomicFile out(file);
  CsvWriter csv(out.stream(), with_episode_columns({"map", "scenario", "eval_seed", "pursuer", "evader"}));
  for (const League::Game& g : games) {
    auto row = csv.row();
    row.add(g.map).add(g.scenario).add(g.eval_seed).add(g.pursuer).add(g.evader);
    add_episode_cells(row, g.result);
    row.end();
  }
  out.commit();
}

nlohmann::ordered_json league_matrix(const League& league, const std::vector<League::Game>& games, bool by_group) {
  std::map<std::string, std::string> key_of;  // entrant name -> its row or column key
  std::vector<std::string> p_keys, e_keys;
  const auto add = [&](const std::vector<Entrant>& entrants, std::vector<std::string>& keys) {
    for (const Entrant& x : entrants) {
      const std::string key = by_group ? x.group : x.name;
      key_of[x.name] = key;
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  };
  add(league.pursuers(), p_keys);
  add(league.evaders(), e_keys);
  // One pass over the games, each into its cell (in game order, so the sums are as a scan per cell gives).
  std::map<std::pair<std::string, std::string>, std::vector<const game::EpisodeResult*>> cells;
  for (const League::Game& g : games) cells[{key_of.at(g.pursuer), key_of.at(g.evader)}].push_back(&g.result);
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const std::string& p : p_keys) {
    for (const std::string& e : e_keys) {
      std::size_t captured = 0, collided = 0;
      std::vector<double> capture_time, survival, pinned;
      const auto& cell = cells[{p, e}];
      for (const game::EpisodeResult* r : cell) {
        captured += r->captured();
        collided += r->collisions > 0;
        if (r->captured()) capture_time.push_back(r->duration);
        survival.push_back(evader_survival(*r));
        pinned.push_back(r->pinned_fraction(game::Role::kEvader));
      }
      out.push_back({{"pursuer", p},
                     {"evader", e},
                     {"games", cell.size()},
                     {"captures", captured},
                     {"capture_rate", rate_json(wilson_interval(captured, cell.size()))},
                     {"capture_time_s", mean_json(mean_interval(capture_time))},
                     {"evader_survival_s", mean_json(mean_interval(survival))},
                     {"collision_games", collided},
                     {"evader_pinned_fraction", num(mean_interval(pinned).mean)}});
    }
  }
  return out;
}

void write_league_matrix_csv(const std::filesystem::path& file, const nlohmann::ordered_json& matrix) {
  AtomicFile out(file);
  CsvWriter csv(out.stream(), {"pursuer", "evader", "games", "captures", "capture_rate", "capture_rate_lo",
                               "capture_rate_hi", "capture_time_s", "capture_time_lo", "capture_time_hi",
                               "evader_survival_s", "evader_survival_lo", "evader_survival_hi", "collision_games",
                               "evader_pinned_fraction"});
  for (const auto& r : matrix) {
    csv.row()
        .add(r["pursuer"].get<std::string>())
        .add(r["evader"].get<std::string>())
        .add(r["games"].get<std::size_t>())
        .add(r["captures"].get<std::size_t>())
        .add(number_or_nan(r["capture_rate"]["rate"]))
        .add(number_or_nan(r["capture_rate"]["lo"]))
        .add(number_or_nan(r["capture_rate"]["hi"]))
        .add(number_or_nan(r["capture_time_s"]["mean"]))
        .add(number_or_nan(r["capture_time_s"]["lo"]))
        .add(number_or_nan(r["capture_time_s"]["hi"]))
        .add(number_or_nan(r["evader_survival_s"]["mean"]))
        .add(number_or_nan(r["evader_survival_s"]["lo"]))
        .add(number_or_nan(r["evader_survival_s"]["hi"]))
        .add(r["collision_games"].get<std::size_t>())
        .add(number_or_nan(r["evader_pinned_fraction"]))
        .end();
  }
  out.commit();
}

nlohmann::ordered_json league_findings(const League& league, const std::vector<League::Game>& games) {
  const LeagueSettings& s = league.settings();
  // Games indexed by (pursuer entrant, evader entrant) -> start key -> result.
  std::map<std::pair<std::string, std::string>, std::map<std::string, const game::EpisodeResult*>> at;
  for (const League::Game& g : games)
    at[{g.pursuer, g.evader}][fmt::format("{}/{}/{}", g.map, g.scenario, g.eval_seed)] = &g.result;
  const auto rate = [&](const std::vector<std::string>& ps, const std::vector<std::string>& es) {
    std::size_t n = 0, c = 0;
    for (const auto& p : ps)
      for (const auto& e : es)
        for (const auto& [key, r] : at[{p, e}]) ++n, c += r->captured();
    return wilson_interval(c, n);
  };
  const auto members = [](const std::vector<Entrant>& entrants, const std::string& group) {
    std::vector<std::string> out;
    for (const Entrant& e : entrants)
      if (e.group == group) out.push_back(e.name);
    return out;
  };
  nlohmann::ordered_json pursuers = nlohmann::ordered_json::array(), evaders = nlohmann::ordered_json::array();
  for (const Algorithm& a : league.algorithms()) {
    const std::vector<std::string> mine = members(league.pursuers(), a.name);
    if (mine.empty()) continue;
    nlohmann::ordered_json against = nlohmann::ordered_json::array();
    for (const auto kind : s.classic_evaders) {
      const std::string e = game::to_string(kind);
      const ProportionInterval own = rate(mine, {e});
      std::string best;
      ProportionInterval best_rate{-1.0, 0.0, 0.0};
      for (const auto c : s.classic_pursuers) {
        const ProportionInterval r = rate({game::to_string(c)}, {e});
        if (r.rate > best_rate.rate) best = game::to_string(c), best_rate = r;
      }
      against.push_back({{"evader", e},
                         {"capture_rate", rate_json(own)},
                         {"best_classic_pursuer", best},
                         {"best_classic_rate", rate_json(best_rate)},
                         {"at_least_as_often", own.rate >= best_rate.rate}});
    }
    const std::vector<std::string> own_evaders = members(league.evaders(), a.name);
    nlohmann::ordered_json entry{{"algorithm", a.name}, {"against_scripted_evaders", std::move(against)}};
    if (!own_evaders.empty()) {
      const ProportionInterval r = rate(mine, own_evaders);
      entry["against_own_evaders"] = {{"capture_rate", rate_json(r)}, {"at_least_95_percent", r.rate >= 0.95}};
    }
    pursuers.push_back(std::move(entry));
  }
  for (const Algorithm& a : league.algorithms()) {
    const std::vector<std::string> mine = members(league.evaders(), a.name);
    if (mine.empty()) continue;
    nlohmann::ordered_json against = nlohmann::ordered_json::array();
    for (const auto kind : s.classic_pursuers) {
      const std::string p = game::to_string(kind);
      // The best scripted evader against this pursuer: the longest mean survival.
      std::string best;
      double best_mean = -1.0;
      for (const auto c : s.classic_evaders) {
        std::vector<double> v;
        for (const auto& [key, r] : at[{p, game::to_string(c)}]) v.push_back(evader_survival(*r));
        const double m = mean_interval(v).mean;
        if (m > best_mean) best = game::to_string(c), best_mean = m;
      }
      // Paired by start and evaluation seed: the trained group's survival (mean over its training seeds)
      // against the best scripted evader's.
      std::vector<double> own, theirs;
      std::size_t escapes = 0, games_own = 0, escapes_best = 0;
      for (const auto& [key, r] : at[{p, best}]) {
        double sum = 0.0;
        int n = 0;
        for (const auto& e : mine) {
          const auto it = at[{p, e}].find(key);
          if (it == at[{p, e}].end()) continue;
          sum += evader_survival(*it->second);
          escapes += !it->second->captured();
          ++games_own, ++n;
        }
        if (n == 0) continue;
        own.push_back(sum / n);
        theirs.push_back(evader_survival(*r));
        escapes_best += !r->captured();
      }
      const PairedTTest t = paired_t_test(own, theirs);
      const WilcoxonTest w = wilcoxon_signed_rank(own, theirs);
      against.push_back({{"pursuer", p},
                         {"survival_s", mean_json(mean_interval(own))},
                         {"best_scripted_evader", best},
                         {"best_scripted_survival_s", mean_json(mean_interval(theirs))},
                         {"paired_starts", t.n},
                         {"mean_difference_s", num(t.mean_difference)},
                         {"paired_t_p", num(t.p_two_sided)},
                         {"wilcoxon_p", num(w.p_two_sided)},
                         {"escape_rate", rate_json(wilson_interval(escapes, games_own))},
                         {"best_scripted_escape_rate", rate_json(wilson_interval(escapes_best, theirs.size()))},
                         {"survives_longer", t.mean_difference > 0.0}});
    }
    evaders.push_back({{"algorithm", a.name}, {"against_classic_pursuers", std::move(against)}});
  }
  return {{"pursuers", std::move(pursuers)}, {"evaders", std::move(evaders)}};
}

std::string league_table(const nlohmann::ordered_json& matrix) {
  std::string s = fmt::format("{:<18} {:<18} {:>6} {:>22} {:>12} {:>20} {:>6} {:>8}\n", "pursuer", "evader", "games",
                              "capture rate [95% CI]", "capture t", "survival t [95% CI]", "coll.", "E pinned");
  for (const auto& r : matrix) {
    s += fmt::format("{:<18} {:<18} {:>6} {:>22} {:>12.1f} {:>20} {:>6} {:>8.3f}\n", r["pursuer"].get<std::string>(),
                     r["evader"].get<std::string>(), r["games"].get<std::size_t>(),
                     fmt::format("{:.2f} [{:.2f}, {:.2f}]", number_or_nan(r["capture_rate"]["rate"]), number_or_nan(r["capture_rate"]["lo"]),
                                 number_or_nan(r["capture_rate"]["hi"])),
                     number_or_nan(r["capture_time_s"]["mean"]),
                     fmt::format("{:.1f} [{:.1f}, {:.1f}]", number_or_nan(r["evader_survival_s"]["mean"]),
                                 number_or_nan(r["evader_survival_s"]["lo"]), number_or_nan(r["evader_survival_s"]["hi"])),
                     r["collision_games"].get<std::size_t>(), number_or_nan(r["evader_pinned_fraction"]));
  }
  return s;
}

}  // namespace peg3d::experiment
