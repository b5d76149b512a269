#include "experiment/league_experiment.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "core/config_json.hpp"
#include "core/random.hpp"
#include "core/validation.hpp"
#include "experiment/generalize_experiment.hpp"
#include "experiment/trial.hpp"
#include "results/codecs.hpp"
#include "results/run_info.hpp"
#include "sweep/progress_reporter.hpp"
#include "sweep/run_journal.hpp"
#include "sweep/sweep_driver.hpp"

namespace peg3d::experiment {
namespace {

bool facl_plays(const game::GameConfig& c, game::Role role) { return players::learns(c.agent(role)); }

int most_agents(const world::Arena& arena, game::Role role) {
  int n = 0;
  for (const auto& s : arena.map().scenarios)
    n = std::max(n, static_cast<int>(role == game::Role::kPursuer ? s.pursuers.size() : s.evaders.size()));
  return n;
}

}  // namespace

std::vector<Entrant> league_entrants(const std::vector<Algorithm>& algorithms, const LeagueSettings& s, game::Role role) {
  std::vector<Entrant> out;
  for (std::size_t a = 0; a < algorithms.size(); ++a) {
    if (!facl_plays(algorithms[a].config.game, role)) continue;
    for (int t = 0; t < s.sweep.repeats; ++t) {
      out.push_back({fmt::format("{}#{}", algorithms[a].name, t), algorithms[a].name, role, std::string(players::kFacl),
                     static_cast<int>(a), t});
    }
  }
  for (const auto& name : role == game::Role::kPursuer ? s.classic_pursuers : s.classic_evaders) {
    out.push_back({name, name, role, name, -1, -1});
  }
  const auto& saved = role == game::Role::kPursuer ? s.saved_pursuers : s.saved_evaders;
  const char* field = role == game::Role::kPursuer ? "--pursuer-entrant" : "--evader-entrant";
  for (std::size_t k = 0; k < saved.size(); ++k) {
    if (saved[k].name.empty()) throw InvalidParameter(field, "(empty)", "needs a name: NAME=FILE");
    for (const Entrant& e : out) {
      if (e.name == saved[k].name) throw InvalidParameter(field, saved[k].name, "names another entrant of the league");
    }
    out.push_back({saved[k].name, saved[k].name, role, std::string(players::kFacl), -1, -1, static_cast<int>(k)});
  }
  return out;
}

League::League(std::shared_ptr<const world::Arena> train, std::vector<LeagueMap> eval_maps, std::vector<Algorithm> algorithms,
               LeagueSettings settings)
    : train_(std::move(train)), maps_(std::move(eval_maps)), algorithms_(std::move(algorithms)), settings_(std::move(settings)) {
  if (algorithms_.empty()) throw InvalidParameter("--algorithms", "(none)", "must name at least one algorithm");
  require_at_least("--train-seeds", settings_.sweep.repeats, 1);
  require_at_least("--eval-seeds", settings_.eval_seeds, 1);
  pursuers_ = league_entrants(algorithms_, settings_, game::Role::kPursuer);
  evaders_ = league_entrants(algorithms_, settings_, game::Role::kEvader);
  for (const Algorithm& a : algorithms_) {
    game::GameConfig training = a.config.game;
    if (settings_.train_heading) training.initial_heading = *settings_.train_heading;
    train_sims_.emplace_back(train_, training);
    pools_.push_back(make_pool(train_, training, a.config.training));
  }
  // Groups: the algorithms, then the classic policies of the role, then its saved policies.
  const int n_alg = static_cast<int>(algorithms_.size());
  pursuer_groups_ = n_alg + static_cast<int>(settings_.classic_pursuers.size() + settings_.saved_pursuers.size());
  evader_groups_ = n_alg + static_cast<int>(settings_.classic_evaders.size() + settings_.saved_evaders.size());
  const game::GameConfig& rules = algorithms_.front().config.game;
  const auto side = [&](game::GameConfig& c, game::Role role, int group) {
    const auto& classic = role == game::Role::kPursuer ? settings_.classic_pursuers : settings_.classic_evaders;
    const auto& saved = role == game::Role::kPursuer ? settings_.saved_pursuers : settings_.saved_evaders;
    const int n_classic = static_cast<int>(classic.size());
    auto& all = role == game::Role::kPursuer ? c.pursuer : c.evader;
    auto& list = role == game::Role::kPursuer ? c.pursuers : c.evaders;
    if (group < n_alg) {
      const game::GameConfig& g = algorithms_[std::size_t(group)].config.game;
      all = role == game::Role::kPursuer ? g.pursuer : g.evader;
      list = role == game::Role::kPursuer ? g.pursuers : g.evaders;
      // Whom a team's agents play against is the team's strategy: its own algorithm's, not the rules'.
      if (role == game::Role::kPursuer) {
        c.team.pursuer_target = g.team.pursuer_target;
      } else {
        c.team.evader_threat = g.team.evader_threat;
      }
    } else if (group < n_alg + n_classic) {
      c = game::with_role_playing(std::move(c), role, classic[std::size_t(group - n_alg)]);
    } else if (const game::AgentConfig* own = saved[std::size_t(group - n_alg - n_classic)].policy->config()) {
      all = *own;
      list.clear();
    }
  };
  for (const LeagueMap& m : maps_) {
    for (int p = 0; p < pursuer_groups_; ++p) {
      for (int e = 0; e < evader_groups_; ++e) {
        game::GameConfig c = rules;
        c.initial_heading = settings_.eval_heading;
        side(c, game::Role::kPursuer, p);
        side(c, game::Role::kEvader, e);
        eval_sims_.emplace_back(m.arena, std::move(c));
        // A saved network reads what its agents observe in the games it plays: refused before any run when not.
        const int n_alg = static_cast<int>(algorithms_.size());
        const int p_saved = p - n_alg - static_cast<int>(settings_.classic_pursuers.size());
        const int e_saved = e - n_alg - static_cast<int>(settings_.classic_evaders.size());
        if (p_saved >= 0) settings_.saved_pursuers[std::size_t(p_saved)].policy->check_fits(eval_sims_.back(), game::Role::kPursuer);
        if (e_saved >= 0) settings_.saved_evaders[std::size_t(e_saved)].policy->check_fits(eval_sims_.back(), game::Role::kEvader);
      }
    }
  }
  trained_pursuers_.resize(training_runs());
  trained_evaders_.resize(training_runs());
  training_.resize(training_runs());
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
  nlohmann::json maps = nlohmann::json::array();
  for (const LeagueMap& m : maps_) maps.push_back({{"name", m.name}, {"map_hash", results::map_content_hash(*m.arena)}});
  nlohmann::json pursuers = settings_.classic_pursuers, evaders = settings_.classic_evaders;
  nlohmann::json setup = setup_header("league", *train_, settings_.sweep);
  setup["eval_maps"] = std::move(maps);
  setup["train_seeds"] = train_seeds();
  setup["eval_seeds"] = settings_.eval_seeds;
  setup["eval_heading"] = config::enum_name(game::kInitialHeadingNames, settings_.eval_heading);
  setup["train_heading"] = settings_.train_heading
                               ? nlohmann::json(config::enum_name(game::kInitialHeadingNames, *settings_.train_heading))
                               : nlohmann::json("config");
  setup["classic_pursuers"] = std::move(pursuers);
  setup["classic_evaders"] = std::move(evaders);
  setup["algorithms"] = algorithms_json(algorithms_);
  // Only when there are any, so that the journals of leagues without them keep their header.
  for (const auto& [key, list] : {std::pair{"saved_pursuers", &settings_.saved_pursuers}, std::pair{"saved_evaders", &settings_.saved_evaders}}) {
    if (list->empty()) continue;
    nlohmann::json entries = nlohmann::json::array();
    for (const SavedEntrant& e : *list) {
      entries.push_back({{"name", e.name}, {"kind", e.policy->kind_name()}, {"hash", e.policy->content_hash}});
    }
    setup[key] = std::move(entries);
  }
  return setup;
}

const players::RoleModels& League::models(int a, int t, game::Role role) const {
  const std::size_t run = std::size_t(a) * std::size_t(train_seeds()) + std::size_t(t);
  return role == game::Role::kPursuer ? trained_pursuers_[run] : trained_evaders_[run];
}

results::LearningCurve League::curve(int a, int t) const {
  const std::size_t run = std::size_t(a) * std::size_t(train_seeds()) + std::size_t(t);
  return {training_[run].episodes, pool_opponent_names(pools_[std::size_t(a)], training_[run].opponents)};
}

std::vector<std::string> classic_policies(const std::vector<std::string>& names, game::Role role, const std::string& flag) {
  std::vector<std::string> out;
  for (const auto& name : names) {
    const players::PlayerInfo& p = players::player_named(name, role, flag);
    if (p.learns()) {
      throw InputError(fmt::format("{}: {} is not a {} (use --algorithms)", flag, p.name,
                                   role == game::Role::kPursuer ? "classic pursuer" : "scripted evader"));
    }
    out.emplace_back(p.name);
  }
  return out;
}

std::optional<game::InitialHeading> heading_named(const std::string& name, const std::string& flag,
                                                  bool config_allowed) {
  if (config_allowed && name == "config") return std::nullopt;
  if (const auto* h = config::enum_value(game::kInitialHeadingNames, name)) return *h;
  throw InvalidParameter(flag, "\"" + name + "\"",
                         config_allowed ? "must be random, chase, facing, plus-x or config"
                                        : "must be random, chase, facing or plus-x");
}

SavedEntrant saved_entrant(const std::string& spec, game::Role role,
                           const std::function<std::filesystem::path(const std::filesystem::path&)>& resolve) {
  const std::size_t eq = spec.find('=');
  const std::filesystem::path file = eq == std::string::npos ? spec : spec.substr(eq + 1);
  return {eq == std::string::npos ? file.stem().string() : spec.substr(0, eq), players::load_saved_policy(resolve(file), role)};
}

std::vector<LeagueMap> league_maps(const std::shared_ptr<const world::Arena>& train,
                                   std::vector<std::shared_ptr<const world::Arena>> evals) {
  if (evals.empty()) evals.push_back(train);
  const std::vector<std::string> names = eval_map_names(evals);
  std::vector<LeagueMap> maps;
  for (std::size_t m = 0; m < evals.size(); ++m) maps.push_back({names[m], evals[m]});
  return maps;
}

std::size_t League::episodes_per_run() const {
  // Progress counts the training episodes and the games, spread over the training runs.
  const std::size_t runs = training_runs();
  return (runs * static_cast<std::size_t>(settings_.sweep.episodes) + games() + runs - 1) / runs;
}

void League::begin(const sweep::SweepControl& control) { settings_.sweep.control = control; }

void League::run_one(std::size_t i) {
  const LeagueSettings& s = settings_;
  const sweep::SweepControl& control = s.sweep.control;
  const int max_p = most_agents(*train_, game::Role::kPursuer), max_e = most_agents(*train_, game::Role::kEvader);
  const std::size_t seeds = std::size_t(train_seeds());
  const std::size_t a = i / seeds, t = i % seeds;
  const std::uint64_t seed = derive_seed(s.sweep.seed, {1, a, t});
  const game::Sim& sim = train_sims_[a];
  players::Lineup lineup;
  players::add_configured(lineup, sim.config(), game::Role::kPursuer, max_p, stream_seed(seed, TrialStream::kPursuer),
                       &trained_pursuers_[i]);
  players::add_configured(lineup, sim.config(), game::Role::kEvader, max_e, stream_seed(seed, TrialStream::kEvader),
                       &trained_evaders_[i]);
  game::SimState state(sim);
  training_[i] = train_lineup({.sim = &sim,
                               .training = algorithms_[a].config.training,
                               .pool = &pools_[a],
                               .scenarios = train_->map().scenarios,
                               .pursuers = max_p,
                               .seed = seed,
                               .episodes = s.sweep.episodes,
                               .stop = control.stop,
                               .progress = control.progress},
                              lineup, state);
  if (control.progress) control.progress->run_done();
}

nlohmann::json League::encode(std::size_t i) const {
  return nlohmann::json{{"pursuers", results::role_models_to_json(trained_pursuers_[i])},
                        {"evaders", results::role_models_to_json(trained_evaders_[i])},
                        {"training", results::episodes_to_json(training_[i].episodes)},
                        {"training_opponent", training_[i].opponents}};
}

void League::restore(std::size_t i, const nlohmann::json& data) {
  trained_pursuers_[i] = results::role_models_from_json(data.at("pursuers"), game::Role::kPursuer);
  trained_evaders_[i] = results::role_models_from_json(data.at("evaders"), game::Role::kEvader);
  training_[i].episodes = results::episodes_from_json(data.at("training"));
  training_[i].opponents = data.at("training_opponent").get<std::vector<int>>();
  check_journaled_opponents(pools_[i / std::size_t(train_seeds())], training_[i].opponents,
                            training_[i].episodes.size());
}

void League::finish(bool root) {
  if (root) games_ = play_games();
}

std::vector<League::Game> League::run(bool root) {
  run_experiment(*this, settings_.sweep.threads, settings_.sweep.control, root);
  return games_;
}

int League::group_of(const Entrant& e) const {
  if (e.algorithm >= 0) return e.algorithm;
  const auto& classic = e.role == game::Role::kPursuer ? settings_.classic_pursuers : settings_.classic_evaders;
  if (e.saved >= 0) return static_cast<int>(algorithms_.size() + classic.size()) + e.saved;
  return static_cast<int>(algorithms_.size()) +
         static_cast<int>(std::find(classic.begin(), classic.end(), e.policy) - classic.begin());
}

void League::play_start(const Start& st, std::span<Game> games) const {
  const LeagueSettings& s = settings_;
  const world::Scenario& scenario = maps_[st.map].arena->map().scenarios[st.scenario];
  const int np = static_cast<int>(scenario.pursuers.size()), ne = static_cast<int>(scenario.evaders.size());
  const std::uint64_t seed = derive_seed(s.sweep.seed, {2, st.map, st.scenario, static_cast<std::uint64_t>(st.seed)});
  game::SimState state(sim_of(st.map, 0, 0));
  for (std::size_t p = 0; p < pursuers_.size(); ++p) {
    for (std::size_t e = 0; e < evaders_.size(); ++e) {
      sweep::throw_if_stopped(s.sweep.control.stop);
      const Entrant& P = pursuers_[p];
      const Entrant& E = evaders_[e];
      const game::Sim& sim = sim_of(st.map, group_of(P), group_of(E));
      players::Lineup lineup;
      if (P.saved >= 0) {
        players::add_saved(lineup, *s.saved_pursuers[std::size_t(P.saved)].policy, sim.config(), game::Role::kPursuer, np,
                           derive_seed(seed, {1}));
      } else if (P.algorithm >= 0) {
        players::add_frozen(lineup, models(P.algorithm, P.train_seed, game::Role::kPursuer), np);
      } else {
        players::add_configured(lineup, sim.config(), game::Role::kPursuer, np, derive_seed(seed, {1}));
      }
      if (E.saved >= 0) {
        players::add_saved(lineup, *s.saved_evaders[std::size_t(E.saved)].policy, sim.config(), game::Role::kEvader, ne,
                           derive_seed(seed, {2}));
      } else if (E.algorithm >= 0) {
        players::add_frozen(lineup, models(E.algorithm, E.train_seed, game::Role::kEvader), ne);
      } else {
        players::add_configured(lineup, sim.config(), game::Role::kEvader, ne, derive_seed(seed, {2}));
      }
      state.forget_maps();  // persistent maps carry nothing from one pairing to the next
      games[p * evaders_.size() + e] = {maps_[st.map].name, scenario.name, st.seed,
                                        P.name, E.name,      evaluate(sim, state, scenario, lineup, seed)};
      if (s.sweep.control.progress) s.sweep.control.progress->episode_done();
    }
  }
}

std::vector<League::Game> League::play_games() const {
  const LeagueSettings& s = settings_;
  std::vector<Start> starts;
  for (std::size_t m = 0; m < maps_.size(); ++m)
    for (std::size_t sc = 0; sc < maps_[m].arena->map().scenarios.size(); ++sc)
      for (int k = 0; k < s.eval_seeds; ++k) starts.push_back({m, sc, k});
  const std::size_t pairings = pursuers_.size() * evaders_.size();
  std::vector<Game> games(starts.size() * pairings);
  // A stop during the games keeps the training runs (journaled): --resume reads them back and plays the games.
  const auto interrupted = [&] {
    const sweep::RunJournal* journal = s.sweep.control.journal;
    return sweep::SweepInterrupted(training_runs(), training_runs(), journal ? journal->file() : std::filesystem::path());
  };
  try {
    sweep::run_indexed(
        starts.size(), s.sweep.threads,
        [&](std::size_t j) { play_start(starts[j], std::span<Game>(games).subspan(j * pairings, pairings)); },
        s.sweep.control.stop);
  } catch (const sweep::RunCancelled&) {
    throw interrupted();
  }
  if (s.sweep.control.stop && s.sweep.control.stop()) throw interrupted();
  return games;
}

}  // namespace peg3d::experiment
