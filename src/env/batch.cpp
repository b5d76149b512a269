#include "env/batch.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <span>

#include <malloc.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/random.hpp"
#include "core/validation.hpp"
#include "game/observation.hpp"
#include "game/scenario_choice.hpp"
#include "players/registry.hpp"
#include "sense/scan_map.hpp"

namespace peg3d::env {

namespace {

// Bytes malloc holds for the process now (its arenas and its own mappings: Bullet allocates through it too).
std::size_t allocated_bytes() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

constexpr std::uint64_t kPolicyStream = 0x706f6c6963790000ULL;  // "policy": the C++ policies' seeds below the root
constexpr std::uint64_t kMixtureStream = 0x6d69787475726500ULL;  // "mixture": which member plays an episode
constexpr std::uint64_t kTeamStream = 0x7465616d00000000ULL;     // "team": a mixture file's draws, shared by a key

}  // namespace

struct Batch::Pool {
  std::vector<std::thread> workers;
  std::mutex m;
  std::condition_variable start, done;
  std::uint64_t generation = 0;
  int pending = 0;
  bool stop = false;
  std::function<void(int)> job;
  std::exception_ptr error;

  explicit Pool(int threads) {
    for (int t = 1; t < threads; ++t) {
      workers.emplace_back([this, t] {
        std::uint64_t seen = 0;
        for (;;) {
          std::function<void(int)> mine;
          {
            std::unique_lock lock(m);
            start.wait(lock, [&] { return stop || generation != seen; });
            if (stop) return;
            seen = generation;
            mine = job;
          }
          std::exception_ptr e;
          try {
            mine(t);
          } catch (...) {
            e = std::current_exception();
          }
          std::lock_guard lock(m);
          if (e && !error) error = e;
          if (--pending == 0) done.notify_one();
        }
      });
    }
  }
  ~Pool() {
    {
      std::lock_guard lock(m);
      stop = true;
    }
    start.notify_all();
    for (auto& w : workers) w.join();
  }
  // Runs job(0) here and job(1..) on the workers; returns when all are done.
  void run(std::function<void(int)> f) {
    {
      std::lock_guard lock(m);
      job = std::move(f);
      pending = int(workers.size());
      error = nullptr;
      ++generation;
    }
    start.notify_all();
    std::exception_ptr mine;
    try {
      job(0);
    } catch (...) {
      mine = std::current_exception();
    }
    std::unique_lock lock(m);
    done.wait(lock, [&] { return pending == 0; });
    if (mine) std::rethrow_exception(mine);
    if (error) std::rethrow_exception(error);
  }
};

Batch::Batch(std::shared_ptr<const world::Arena> arena, game::GameConfig config, BatchSettings settings)
    : settings_(std::move(settings)) {
  require_in_range("games", settings_.games, 1, 65536);
  require_in_range("threads", settings_.threads, 1, 256);
  require_in_range("neighbours", settings_.neighbours, 0, 16);
  settings_.threads = std::min(settings_.threads, settings_.games);
  scenarios_ = game::scenarios_of_one_team_size(arena->map(), settings_.scenarios, "scenario");
  const world::Scenario& first = arena->map().scenarios[std::size_t(scenarios_.front())];
  pursuers_ = int(first.pursuers.size());
  agents_ = first.agents();
  for (int i = 0; i < agents_; ++i) {
    names_.push_back(game::agent_label(game::role_at(i, pursuers_), game::rank_at(i, pursuers_)));
  }
  // Per agent, the key of settings_.controllers that names it last (-1: the caller's agent).
  mixture_key_.assign(std::size_t(agents_), -1);
  for (std::size_t k = 0; k < settings_.controllers.size(); ++k) {
    const auto& [key, entries] = settings_.controllers[k];
    bool matched = false;
    for (int i = 0; i < agents_; ++i) {
      const bool pursuer = i < pursuers_;
      if (key == names_[std::size_t(i)] || key == (pursuer ? "pursuer" : "evader")) {
        mixture_key_[std::size_t(i)] = int(k);
        matched = true;
      }
    }
    if (!matched) {
      throw InvalidParameter("opponents." + key, entries.empty() ? "" : entries.front().policy,
                             "names no agent of the game (pursuer_0.., evader_0.., pursuer, evader)");
    }
  }
  mixtures_.resize(std::size_t(agents_));
  weights_.resize(std::size_t(agents_));
  for (int i = 0; i < agents_; ++i) {
    const int k = mixture_key_[std::size_t(i)];
    if (k < 0) continue;
    const auto& [key, entries] = settings_.controllers[std::size_t(k)];
    const std::string field = "opponents." + key;
    if (entries.empty() || (entries.size() == 1 && entries.front().policy.empty())) {
      mixture_key_[std::size_t(i)] = -1;  // given back to the caller
      continue;
    }
    if (entries.size() > std::size_t(kMaxMixtureEntries)) {
      throw InvalidParameter(field, std::to_string(entries.size()) + " members",
                             "a mixture has at most " + std::to_string(kMaxMixtureEntries));
    }
    // A member's field: the key's for a lone member, else the key's and its place.
    const auto member_field = [&](std::size_t e) { return entries.size() == 1 ? field : field + "." + std::to_string(e); };
    std::vector<Member>& mixture = mixtures_[std::size_t(i)];
    for (std::size_t e = 0; e < entries.size(); ++e) mixture.push_back(resolve_member(i, entries[e], member_field(e)));
    if (const players::MixtureProblem problem = players::check_mixture(mixture); !problem.message.empty()) {
      if (problem.member < 0) throw InvalidParameter(field, "", problem.message);
      const auto e = std::size_t(problem.member);
      throw InvalidParameter(problem.field == "weight" ? member_field(e) + ".weight" : member_field(e),
                             problem.field == "weight" ? fmt::format("{}", entries[e].weight) : entries[e].policy,
                             problem.message);
    }
    for (const Member& m : mixture) weights_[std::size_t(i)].push_back(m.weight);
    // A mixture's FACL files carry their agent configuration; the agent plays under it, whichever member plays.
    if (const game::AgentConfig* own = players::mixture_config(mixture)) {
      config.set_agent(game::role_at(i, pursuers_), game::rank_at(i, pursuers_), *own);
    }
  }
  sim_ = std::make_shared<const game::Sim>(std::move(arena), std::move(config));
  for (int i = 0; i < agents_; ++i) {
    const game::Role role = game::role_at(i, pursuers_);
    const int rank = game::rank_at(i, pursuers_);
    tables_.push_back(game::observation_table(*sim_, role, rank, settings_.neighbours));
    stride_ = std::max(stride_, tables_.back().size());
    // A C++-played network reads what this batch would give its agent: refused before any game when it cannot.
    for (const Member& c : mixtures_[std::size_t(i)]) {
      if (c.saved) c.saved->check_fits(*sim_, role, rank);
    }
  }
  games_.reserve(std::size_t(settings_.games));
  const std::size_t before = allocated_bytes();
  games_.emplace_back(*sim_);
  const std::size_t after = allocated_bytes();
  check_memory_budget(after > before ? after - before : 0);
  for (int g = 1; g < settings_.games; ++g) games_.emplace_back(*sim_);
  if (settings_.record) {
    games_.front().trace = std::make_unique<game::Trace>();
    games_.front().trace->reserve(sim_->max_steps(), agents_);
  }
  const std::size_t n = std::size_t(settings_.games) * std::size_t(agents_);
  observations_.assign(n * std::size_t(stride_), 0.0f);
  rewards_.assign(n, 0.0f);
  terms_.assign(n * 3, 0.0f);
  terminated_.assign(n, 0);
  truncated_.assign(n, 0);
  acted_.assign(n, 0);
  active_.assign(n, 0);
  collided_.assign(n, 0);
  captured_.assign(n, 0);
  reset_flags_.assign(std::size_t(settings_.games), 0);
  pool_ = std::make_unique<Pool>(settings_.threads);
  reset(settings_.seed);
}

Batch::~Batch() = default;

void Batch::check_memory_budget(std::size_t state_bytes) const {
  // The first game, built before this call, is measured as it stands (its SimState: Bullet's collision world,
  // scratch, sensors); its own maps are made at its first reset, so they are counted from their settings.
  std::size_t budget = settings_.memory_budget;
  if (budget == 0) {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    budget = pages > 0 && page > 0 ? std::size_t(pages) / 4 * 3 * std::size_t(page) : std::size_t{8} << 30;
  }
  std::size_t maps = 0;
  for (int i = 0; i < agents_; ++i) {
    const game::AgentConfig& a = sim_->config().agent_at(i, pursuers_);
    if (!a.map.enabled) continue;
    // A map holds the bricks its scans reach: at most those of an episode's scans (a reset's and one a period),
    // or with map.persist those of every episode, so the whole arena's.
    int rays = 0, period = 0;
    double range = 0.0;
    const game::Role role = i < pursuers_ ? game::Role::kPursuer : game::Role::kEvader;
    for (const sense::Sensor* s : sim_->sensors(role, i < pursuers_ ? i : i - pursuers_)) {
      if (s->map_range() <= 0.0) continue;
      rays += s->map_points_max();
      range = std::max(range, s->map_range());
      period = period == 0 ? s->period() : std::min(period, s->period());
    }
    const long long scans = a.map.persist || period == 0 ? -1 : sim_->max_steps() / period + 2;
    maps += sense::ScanMap::bytes_most(a.map, sim_->arena().bounds().lo, sim_->arena().bounds().hi, rays, range, scans);
  }
  const std::size_t arrays = std::size_t(agents_) * (std::size_t(stride_) * sizeof(float) + 8 * sizeof(float));
  const std::size_t per_game = state_bytes + maps + arrays;
  const double total = double(per_game) * double(settings_.games);
  if (total > double(budget)) {
    const auto mb = [](double bytes) { return fmt::format("{:.1f} MB", bytes / 1e6); };
    throw MemoryBudgetError(
        {}, 0, "memory_budget",
        fmt::format("{} games of about {} each ({} for a game's state, {} for its agents' own maps) would take "
                    "about {}, more than the memory budget of {}: play fewer games, coarser maps, or raise "
                    "memory_budget (bytes; by default three quarters of this machine's memory)",
                    settings_.games, mb(double(per_game)), mb(double(state_bytes)), mb(double(maps)), mb(total),
                    mb(double(budget))));
  }
}

Batch::Member Batch::resolve_member(int i, const MixtureEntry& entry, const std::string& field) const {
  const game::Role role = i < pursuers_ ? game::Role::kPursuer : game::Role::kEvader;
  const std::string& source = entry.policy;
  Member m;
  m.weight = entry.weight;
  std::error_code ec;
  if (source.find('/') != std::string::npos || source.ends_with(".json") || std::filesystem::exists(source, ec)) {
    m.saved = players::load_saved_policy(source, role);
    return m;
  }
  if (source.empty()) throw InvalidParameter(field, source, "a mixture's member names a policy or a policy file");
  const players::PlayerInfo& player = players::player_named(source, role, field);
  m.player = std::string(player.name);
  if (player.learns()) {
    throw InvalidParameter(field, source, "a FACL opponent plays a saved policy: give its file");
  }
  return m;
}

std::vector<MixtureEntry> Batch::mixture(int i) const {
  require_in_range("agent", i, 0, agents_ - 1);
  std::vector<MixtureEntry> out;
  const int k = mixture_key_[std::size_t(i)];
  if (k >= 0) out = settings_.controllers[std::size_t(k)].second;
  return out;
}

void Batch::build_policies(int g) {
  Game& game = games_[std::size_t(g)];
  game.players.clear();
  game.players.resize(std::size_t(agents_));
  game.member.assign(std::size_t(agents_), -1);
  game.policies.assign(std::size_t(agents_), nullptr);
  game.commands.assign(std::size_t(agents_), Steering{});
  for (int i = 0; i < agents_; ++i) {
    const std::vector<Member>& mixture = mixtures_[std::size_t(i)];
    for (std::size_t e = 0; e < mixture.size(); ++e) {
      const Member& c = mixture[e];
      // A lone member keeps the seed a single C++ player has always had; a mixture's members have their own.
      const std::uint64_t seed =
          mixture.size() == 1 ? derive_seed(game.seed, {game.slot, kPolicyStream, std::uint64_t(i)})
                              : derive_seed(game.seed, {game.slot, kPolicyStream, std::uint64_t(i), std::uint64_t(e)});
      const game::Role role = i < pursuers_ ? game::Role::kPursuer : game::Role::kEvader;
      game::AgentConfig a = sim_->config().agent(role, i < pursuers_ ? i : i - pursuers_);
      if (c.saved) {
        // A mixture file's draws are its key's: the agents of one key play the same member of it.
        const std::uint64_t team = derive_seed(
            game.seed, {game.slot, kTeamStream, std::uint64_t(mixture_key_[std::size_t(i)]), std::uint64_t(e)});
        game.players[std::size_t(i)].push_back(c.saved->make(seed, a, role, team));
      } else {
        a.policy = c.player;
        game.players[std::size_t(i)].push_back(players::make_player(a, role, seed));
      }
    }
  }
}

void Batch::choose_members(int g) {
  Game& game = games_[std::size_t(g)];
  for (int i = 0; i < agents_; ++i) {
    const std::vector<Member>& mixture = mixtures_[std::size_t(i)];
    if (mixture.empty()) continue;
    int chosen = 0;
    if (mixture.size() > 1) {
      // One draw per key and episode, shared by the key's agents: the cumulative weights against a uniform in [0, 1).
      const int key = mixture_key_[std::size_t(i)];
      const std::uint64_t bits = derive_seed(
          game.seed, {game.slot, kMixtureStream, std::uint64_t(game.episode), std::uint64_t(key)});
      chosen = players::draw_member(weights_[std::size_t(i)], bits);
    }
    game.member[std::size_t(i)] = chosen;
    game.policies[std::size_t(i)] = game.players[std::size_t(i)][std::size_t(chosen)].get();
  }
}

std::vector<std::string> Batch::scenario_names() const {
  std::vector<std::string> names;
  for (const int i : scenarios_) names.push_back(sim_->arena().map().scenarios[std::size_t(i)].name);
  return names;
}

const world::Scenario& Batch::scenario_for(int g, long long episode) const {
  const auto& all = sim_->arena().map().scenarios;
  const long long slot = (long long)games_[std::size_t(g)].slot;
  return all[std::size_t(scenarios_[std::size_t((slot + episode) % (long long)scenarios_.size())])];
}

void Batch::start_episode(int g) {
  Game& game = games_[std::size_t(g)];
  game::reset(*sim_, game.state, scenario_for(g, game.episode), derive_seed(game.seed, {game.slot, std::uint64_t(game.episode)}));
  choose_members(g);
  for (int i = 0; i < agents_; ++i) {
    if (game.policies[std::size_t(i)]) game::begin_playing(*sim_, game.state, i, *game.policies[std::size_t(i)], false);
  }
  const std::size_t base = std::size_t(g) * std::size_t(agents_);
  for (int i = 0; i < agents_; ++i) {
    const std::size_t k = base + std::size_t(i);
    rewards_[k] = 0.0f;
    terms_[3 * k] = terms_[3 * k + 1] = terms_[3 * k + 2] = 0.0f;
    terminated_[k] = truncated_[k] = acted_[k] = collided_[k] = captured_[k] = 0;
  }
  reset_flags_[std::size_t(g)] = 1;
  if (game.trace) {
    game.trace->clear();
    game.trace->record(game.state, false);
  }
  write_outputs(g);
}

void Batch::reset(std::optional<std::uint64_t> seed) {
  if (seed) settings_.seed = *seed;
  for (int g = 0; g < settings_.games; ++g) {
    Game& game = games_[std::size_t(g)];
    if (seed) {
      game.seed = *seed;
      game.slot = std::uint64_t(g);
      build_policies(g);
    }
    game.episode = seed ? 0 : game.episode + 1;
    start_episode(g);
  }
}

void Batch::reset_game(int g, std::optional<std::uint64_t> seed) {
  require_in_range("game", g, 0, settings_.games - 1);
  Game& game = games_[std::size_t(g)];
  if (seed) {
    game.seed = *seed;
    game.slot = 0;
    build_policies(g);
  }
  game.episode = seed ? 0 : game.episode + 1;
  start_episode(g);
}

void Batch::step_game(int g, const double* actions) {
  Game& game = games_[std::size_t(g)];
  reset_flags_[std::size_t(g)] = 0;
  if (game.state.done) {
    ++game.episode;
    start_episode(g);
    return;
  }
  for (int i = 0; i < agents_; ++i) {
    const game::AgentState& a = game.state.agents[std::size_t(i)];
    Steering& u = game.commands[std::size_t(i)];
    if (!a.active) {
      u = {};
    } else if (game::Policy* p = game.policies[std::size_t(i)]) {
      u = p->act(a.view);
    } else {
      const double* x = actions + (std::size_t(g) * std::size_t(agents_) + std::size_t(i)) * 2;
      u = {x[0], x[1]};
    }
  }
  const game::StepEvents& ev = step_or_name(g);
  if (game.trace) game.trace->record(game.state, true);
  const std::size_t base = std::size_t(g) * std::size_t(agents_);
  for (int i = 0; i < agents_; ++i) {
    const game::AgentEvents& e = ev.agents[std::size_t(i)];
    const std::size_t k = base + std::size_t(i);
    rewards_[k] = float(e.reward.total);
    terms_[3 * k] = float(e.reward.obstacle);
    terms_[3 * k + 1] = float(e.reward.target);
    terms_[3 * k + 2] = float(e.reward.success);
    acted_[k] = e.acted;
    terminated_[k] = e.acted && (e.terminal || ev.terminal);
    truncated_[k] = e.acted && !terminated_[k] && ev.truncated;
    collided_[k] = e.collided;
    captured_[k] = e.captured;
  }
  write_outputs(g);
}

void Batch::run_on_threads(void (Batch::*work)(int, const double*), const double* actions) {
  const int threads = settings_.threads, n = settings_.games;
  pool_->run([&](int t) {
    const int lo = int((long long)n * t / threads), hi = int((long long)n * (t + 1) / threads);
    for (int g = lo; g < hi; ++g) (this->*work)(g, actions);
  });
}

const game::StepEvents& Batch::step_or_name(int g) {
  Game& game = games_[std::size_t(g)];
  try {
    return game::step(*sim_, game.state, game.commands);
  } catch (const game::CommandError& e) {
    const game::Policy* p = e.agent() >= 0 ? game.policies[std::size_t(e.agent())] : nullptr;
    throw (p != nullptr && !p->file().empty() ? e.played_by(p->file()) : e).in_game(g);
  }
}

void Batch::step(const double* actions) {
  // The caller's actions, by the game's own check, before anything acts or steps. A scan of the flat array
  // passes finite values without touching the games' states; only a value that is not finite is put to the
  // game (which ignores it for an agent out of the game, a C++-played agent, or a game this step resets).
  const std::size_t count = std::size_t(settings_.games) * std::size_t(agents_);
  for (std::size_t k = 0; k < count; ++k) {
    const double* x = actions + 2 * k;
    if (std::isfinite(x[0]) && std::isfinite(x[1])) [[likely]] continue;
    const int g = static_cast<int>(k / std::size_t(agents_)), i = static_cast<int>(k % std::size_t(agents_));
    const game::SimState& st = games_[std::size_t(g)].state;
    if (st.done || controlled(i)) continue;
    try {
      game::check_command(st, i, {x[0], x[1]});
    } catch (const game::CommandError& e) {
      throw e.in_game(g);
    }
  }
  run_on_threads(&Batch::step_game, actions);
}

void Batch::write_outputs(int g) {
  const game::SimState& st = games_[std::size_t(g)].state;
  for (int i = 0; i < agents_; ++i) {
    const game::AgentState& a = st.agents[std::size_t(i)];
    const auto row = std::span<float>(observations_).subspan((std::size_t(g) * std::size_t(agents_) + std::size_t(i)) * std::size_t(stride_),
                                                             std::size_t(stride_));
    const game::ObservationTable& table = tables_[std::size_t(i)];
    game::write_observation(*sim_, st, i, table, row);
    std::fill(row.begin() + table.size(), row.end(), 0.0f);  // a smaller observation's row ends in zeros
    active_[std::size_t(g) * std::size_t(agents_) + std::size_t(i)] = a.active && !st.done;
  }
}

ObservationBounds Batch::observation_bounds(int i) const {
  ObservationBounds b;
  for (const sense::Segment& s : tables_[std::size_t(i)].segments) {
    b.low.insert(b.low.end(), s.low.begin(), s.low.end());
    b.high.insert(b.high.end(), s.high.begin(), s.high.end());
  }
  return b;
}

double Batch::action_bound(game::Role role) const {
  double bound = sim_->config().agent(role, 0).steering.step_bound(sim_->config().dt);
  return bound;
}

ObservationBounds Batch::state_bounds() const {
  const Box& box = sim_->arena().bounds();
  ObservationBounds b;
  const auto add = [&](double lo, double hi) {
    b.low.push_back(float(lo));
    b.high.push_back(float(hi));
  };
  for (int i = 0; i < agents_; ++i) {
    for (int k = 0; k < 3; ++k) add(box.lo[k], box.hi[k]);
    add(-kPi, kPi);
    add(0.0, kPi);
    add(0.0, 1.0);
  }
  add(0.0, sim_->config().time_limit + sim_->config().dt);
  return b;
}

std::vector<float> Batch::global_state(int game) const {
  const game::SimState& st = games_[std::size_t(game)].state;
  std::vector<float> s;
  s.reserve(std::size_t(global_state_size()));
  for (const game::AgentState& a : st.agents) {
    for (int k = 0; k < 3; ++k) s.push_back(float(a.kinematics.position[k]));
    s.push_back(float(a.kinematics.heading.alpha));
    s.push_back(float(a.kinematics.heading.theta));
    s.push_back(a.active ? 1.0f : 0.0f);
  }
  s.push_back(float(st.time));
  return s;
}

}  // namespace peg3d::env
