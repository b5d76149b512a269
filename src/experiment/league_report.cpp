#include "experiment/league_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "players/policy_io.hpp"
#include "results/csv_writer.hpp"
#include "results/result_files.hpp"
#include "results/statistics.hpp"

namespace peg3d::experiment {
namespace {

/// Time each evader of the game stayed free, on average: its capture time, or the game's end.
double evader_survival(const game::EpisodeResult& r) {
  const int free = r.evaders - r.captures;
  return (r.capture_time_sum + free * r.duration) / std::max(1, r.evaders);
}

nlohmann::ordered_json num(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); }

/// The inverse of num(): a JSON number, or NaN for null.
double number_or_nan(const nlohmann::ordered_json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

nlohmann::ordered_json mean_json(const results::MeanInterval& m) {
  return {{"mean", num(m.mean)}, {"lo", num(m.lo)}, {"hi", num(m.hi)}, {"n", m.n}};
}

nlohmann::ordered_json rate_json(const results::ProportionInterval& r) { return {{"rate", num(r.rate)}, {"lo", r.lo}, {"hi", r.hi}}; }

}  // namespace

void write_league_learning_curves_csv(const std::filesystem::path& file, const League& league) {
  AtomicFile out(file);
  results::CsvWriter csv(out.stream(),
                results::with_episode_columns({"algorithm", "train_seed", "episode", "scenario", "pool_opponent"}));
  const auto& scenarios = league.train_arena().map().scenarios;
  for (std::size_t a = 0; a < league.algorithms().size(); ++a) {
    for (int t = 0; t < league.train_seeds(); ++t) {
      const results::LearningCurve c = league.curve(static_cast<int>(a), t);
      for (std::size_t e = 0; e < c.episodes.size(); ++e) {
        auto row = csv.row();
        row.add(league.algorithms()[a].name).add(t).add(e).add(scenarios[e % scenarios.size()].name).add(c.pool_opponents[e]);
        results::add_episode_cells(row, c.episodes[e]);
        row.end();
      }
    }
  }
  out.commit();
}

void write_league_games_csv(const std::filesystem::path& file, const std::vector<League::Game>& games) {
  AtomicFile out(file);
  results::CsvWriter csv(out.stream(), results::with_episode_columns({"map", "scenario", "eval_seed", "pursuer", "evader"}));
  for (const League::Game& g : games) {
    auto row = csv.row();
    row.add(g.map).add(g.scenario).add(g.eval_seed).add(g.pursuer).add(g.evader);
    results::add_episode_cells(row, g.result);
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
                     {"capture_rate", rate_json(results::wilson_interval(captured, cell.size()))},
                     {"capture_time_s", mean_json(results::mean_interval(capture_time))},
                     {"evader_survival_s", mean_json(results::mean_interval(survival))},
                     {"collision_games", collided},
                     {"evader_pinned_fraction", num(results::mean_interval(pinned).mean)}});
    }
  }
  return out;
}

void write_league_matrix_csv(const std::filesystem::path& file, const nlohmann::ordered_json& matrix) {
  AtomicFile out(file);
  results::CsvWriter csv(out.stream(), {"pursuer", "evader", "games", "captures", "capture_rate", "capture_rate_lo",
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

namespace {

// The games by (pursuer entrant, evader entrant), then by start ("map/scenario/seed").
class GameIndex {
 public:
  explicit GameIndex(const std::vector<League::Game>& games) {
    for (const League::Game& g : games)
      at_[{g.pursuer, g.evader}][fmt::format("{}/{}/{}", g.map, g.scenario, g.eval_seed)] = &g.result;
  }
  const std::map<std::string, const game::EpisodeResult*>& of(const std::string& p, const std::string& e) {
    return at_[{p, e}];
  }
  /// The capture rate of pursuers `ps` against evaders `es`, over all their games.
  results::ProportionInterval rate(const std::vector<std::string>& ps, const std::vector<std::string>& es) {
    std::size_t n = 0, c = 0;
    for (const auto& p : ps)
      for (const auto& e : es)
        for (const auto& [key, r] : of(p, e)) ++n, c += r->captured();
    return results::wilson_interval(c, n);
  }

 private:
  std::map<std::pair<std::string, std::string>, std::map<std::string, const game::EpisodeResult*>> at_;
};

std::vector<std::string> members(const std::vector<Entrant>& entrants, const std::string& group) {
  std::vector<std::string> out;
  for (const Entrant& e : entrants)
    if (e.group == group) out.push_back(e.name);
  return out;
}

// A trained pursuer group (`mine`) against each scripted evader beside the best classic pursuer, and against
// its own group's evaders.
nlohmann::ordered_json pursuer_finding(const League& league, GameIndex& games, const std::string& group,
                                       const std::vector<std::string>& mine) {
  const LeagueSettings& s = league.settings();
  nlohmann::ordered_json against = nlohmann::ordered_json::array();
  for (const std::string& e : s.classic_evaders) {
    const results::ProportionInterval own = games.rate(mine, {e});
    std::string best;
    results::ProportionInterval best_rate{-1.0, 0.0, 0.0};
    for (const std::string& c : s.classic_pursuers) {
      const results::ProportionInterval r = games.rate({c}, {e});
      if (r.rate > best_rate.rate) best = c, best_rate = r;
    }
    against.push_back({{"evader", e},
                       {"capture_rate", rate_json(own)},
                       {"best_classic_pursuer", best},
                       {"best_classic_rate", rate_json(best_rate)},
                       {"at_least_as_often", own.rate >= best_rate.rate}});
  }
  const std::vector<std::string> own_evaders = members(league.evaders(), group);
  nlohmann::ordered_json entry{{"algorithm", group}, {"against_scripted_evaders", std::move(against)}};
  if (!own_evaders.empty()) {
    const results::ProportionInterval r = games.rate(mine, own_evaders);
    entry["against_own_evaders"] = {{"capture_rate", rate_json(r)}, {"at_least_95_percent", r.rate >= 0.95}};
  }
  return entry;
}

// A trained evader group (`mine`) against classic pursuer `p`: its survival beside the best scripted evader's,
// paired by start and evaluation seed (the group's survival is the mean over its training seeds).
nlohmann::ordered_json evader_against(const League& league, GameIndex& games, const std::string& p,
                                      const std::vector<std::string>& mine) {
  // The best scripted evader against this pursuer: the longest mean survival.
  std::string best;
  double best_mean = -1.0;
  for (const std::string& c : league.settings().classic_evaders) {
    std::vector<double> v;
    for (const auto& [key, r] : games.of(p, c)) v.push_back(evader_survival(*r));
    const double m = results::mean_interval(v).mean;
    if (m > best_mean) best = c, best_mean = m;
  }
  std::vector<double> own, theirs;
  std::size_t escapes = 0, games_own = 0, escapes_best = 0;
  for (const auto& [key, r] : games.of(p, best)) {
    double sum = 0.0;
    int n = 0;
    for (const auto& e : mine) {
      const auto& played = games.of(p, e);
      const auto it = played.find(key);
      if (it == played.end()) continue;
      sum += evader_survival(*it->second);
      escapes += !it->second->captured();
      ++games_own, ++n;
    }
    if (n == 0) continue;
    own.push_back(sum / n);
    theirs.push_back(evader_survival(*r));
    escapes_best += !r->captured();
  }
  const results::PairedTTest t = results::paired_t_test(own, theirs);
  const results::WilcoxonTest w = results::wilcoxon_signed_rank(own, theirs);
  return {{"pursuer", p},
          {"survival_s", mean_json(results::mean_interval(own))},
          {"best_scripted_evader", best},
          {"best_scripted_survival_s", mean_json(results::mean_interval(theirs))},
          {"paired_starts", t.n},
          {"mean_difference_s", num(t.mean_difference)},
          {"paired_t_p", num(t.p_two_sided)},
          {"wilcoxon_p", num(w.p_two_sided)},
          {"escape_rate", rate_json(results::wilson_interval(escapes, games_own))},
          {"best_scripted_escape_rate", rate_json(results::wilson_interval(escapes_best, theirs.size()))},
          {"survives_longer", t.mean_difference > 0.0}};
}

}  // namespace

nlohmann::ordered_json league_findings(const League& league, const std::vector<League::Game>& games) {
  GameIndex index(games);
  nlohmann::ordered_json pursuers = nlohmann::ordered_json::array(), evaders = nlohmann::ordered_json::array();
  for (const Algorithm& a : league.algorithms()) {
    const std::vector<std::string> mine = members(league.pursuers(), a.name);
    if (!mine.empty()) pursuers.push_back(pursuer_finding(league, index, a.name, mine));
  }
  for (const Algorithm& a : league.algorithms()) {
    const std::vector<std::string> mine = members(league.evaders(), a.name);
    if (mine.empty()) continue;
    nlohmann::ordered_json against = nlohmann::ordered_json::array();
    for (const std::string& name : league.settings().classic_pursuers) {
      against.push_back(evader_against(league, index, name, mine));
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

void League::write_results(const std::filesystem::path& out, const SweepTiming&) const {
  std::filesystem::create_directories(out / "policies");
  for (std::size_t a = 0; a < algorithms().size(); ++a) {
    for (int t = 0; t < train_seeds(); ++t) {
      for (const game::Role role : {game::Role::kPursuer, game::Role::kEvader}) {
        const auto& trained = models(static_cast<int>(a), t, role).models;
        for (std::size_t k = 0; k < trained.size(); ++k) {
          const std::string key = fmt::format("{}_{}_{}{}", algorithms()[a].name, t, game::to_string(role),
                                              k == 0 ? std::string() : fmt::format("_{}", k));
          players::save_policy(results::output_file(out / "policies", key, ".json"), *trained[k]);
        }
      }
    }
  }
  const auto matrix = league_matrix(*this, games_, /*by_group=*/true);
  const auto entrants = league_matrix(*this, games_, /*by_group=*/false);
  write_league_games_csv(out / "games.csv", games_);
  write_league_learning_curves_csv(out / "learning_curves.csv", *this);
  write_league_matrix_csv(out / "matrix.csv", matrix);
  write_league_matrix_csv(out / "matrix_entrants.csv", entrants);
  results::write_json(out / "summary.json", nlohmann::ordered_json{{"matrix", matrix},
                                                                   {"entrants", entrants},
                                                                   {"findings", league_findings(*this, games_)}});
}

std::vector<std::pair<std::string, const world::Arena*>> League::maps() const {
  std::vector<std::pair<std::string, const world::Arena*>> maps{{"train", &train_arena()}};
  for (const LeagueMap& m : eval_maps()) maps.emplace_back("eval " + m.name, m.arena.get());
  return maps;
}

nlohmann::ordered_json League::run_info() const {
  return {{"setup", setup()},
          {"seeds", {{"root", settings().sweep.seed},
                     {"derivation", "training run (a, t) = derive_seed(root, {1, a, t}); game at (map m, scenario s, "
                                    "evaluation seed k) = derive_seed(root, {2, m, s, k}) for every pairing, its classic "
                                    "pursuers derive_seed(game, {1}), scripted evaders derive_seed(game, {2})"}}}};
}

std::string League::report(const SweepTiming&) const {
  return league_table(league_matrix(*this, games_, /*by_group=*/true));
}

}  // namespace peg3d::experiment
