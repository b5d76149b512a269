// peg-throughput: full training steps per second of the game on a map, and where each step's time goes
// (docs/performance.md). Every thread co-trains its own set of learners (the configuration's policies),
// playing the map's scenarios in turn as a trial does, with learning, collisions and distance queries on.
// Prints one JSON object on stdout.
//   peg-throughput [--map MAP] [--steps N] [--threads T] [--config C] [--set k=v]... [--no-breakdown]
//   peg-throughput --actions random [--games N] ...: the env-only work of the Python vector env (env/batch.hpp):
//     N games stepped together on T threads with uniform random steering within the bound, no learning, no
//     breakdown; the figure to hold python/bench_vector_env.py against (docs/performance.md).
// Two passes: the headline pass runs without the breakdown; a second pass of the same length records the
// time of each part (StepProfile, a few nanoseconds per part) and reports it per step, with what that
// recording cost.

#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "core/random.hpp"
#include "core/step_profile.hpp"
#include "env/batch.hpp"
#include "game/config_file.hpp"
#include "players/registry.hpp"
#include "game/episode.hpp"
#include "players/lineup.hpp"
#include "world/bodies/mover_timeline.hpp"

using namespace peg3d;

namespace {

struct Pass {
  double seconds = 0.0;
  long long steps = 0, agent_steps = 0, episodes = 0;
  long long contact_give_ups = 0;  // mover contact searches that reached their bound (game::StepEvents)
  StepProfile profile;  // summed over threads (empty unless recorded)
};

// Each thread plays episodes until it has made its share of the steps.
Pass run_pass(const game::Sim& sim, long long steps, int threads, bool profiled) {
  const auto& scenarios = sim.arena().map().scenarios;
  std::vector<Pass> per(static_cast<std::size_t>(threads));
  const auto work = [&](int t) {
    Pass& mine = per[std::size_t(t)];
    if (profiled) StepProfile::current() = &mine.profile;
    game::SimState st(sim);
    const world::Scenario& first = scenarios.front();
    players::Lineup lineup;
    players::add_configured(lineup, sim.config(), game::Role::kPursuer, int(first.pursuers.size()), derive_seed(1, {std::uint64_t(t)}));
    players::add_configured(lineup, sim.config(), game::Role::kEvader, int(first.evaders.size()), derive_seed(2, {std::uint64_t(t)}));
    const long long share = steps / threads + (t < steps % threads ? 1 : 0);
    for (std::uint64_t episode = 0; mine.steps < share; ++episode) {
      const world::Scenario& s = scenarios[episode % scenarios.size()];
      const game::EpisodeResult r = game::play(sim, st, s, lineup.policies(), true, derive_seed(3, {std::uint64_t(t), episode}));
      const int n = r.steps;
      mine.contact_give_ups += r.contact_give_ups;
      mine.steps += n;
      mine.agent_steps += static_cast<long long>(n) * s.agents();
      ++mine.episodes;
    }
    StepProfile::current() = nullptr;
  };
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  Pass total;
  total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const Pass& p : per) {
    total.steps += p.steps, total.agent_steps += p.agent_steps, total.episodes += p.episodes;
    total.contact_give_ups += p.contact_give_ups;
    for (int k = 0; k < StepProfile::kPartCount; ++k) total.profile.ticks[std::size_t(k)] += p.profile.ticks[std::size_t(k)];
  }
  return total;
}

// The batch of `games` games stepped with uniform random steering until `steps` env steps are made; returns the
// seconds of the stepping (the actions' drawing included, as the Python benchmark draws its own).
Pass run_random_batch(const game::Sim& sim, long long steps, int games, int threads) {
  env::BatchSettings settings;
  settings.games = games;
  settings.threads = threads;
  settings.seed = 1;
  env::Batch batch(sim.arena_ptr(), sim.config(), settings);
  const double bound = batch.action_bound(game::Role::kPursuer);
  const double evader_bound = batch.action_bound(game::Role::kEvader);
  std::vector<double> actions(std::size_t(games) * std::size_t(batch.agents()) * 2);
  Rng rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Pass pass;
  const auto start = std::chrono::steady_clock::now();
  while (pass.steps < steps) {
    for (std::size_t k = 0; k < actions.size(); ++k) {
      const bool pursuer = int(k / 2 % std::size_t(batch.agents())) < batch.pursuers();
      actions[k] = unit(rng) * (pursuer ? bound : evader_bound);
    }
    batch.step(actions.data());
    pass.steps += games;
    pass.agent_steps += static_cast<long long>(games) * batch.agents();
  }
  pass.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return pass;
}

// Nanoseconds per time-stamp-counter tick, against the steady clock over a short sleep.
double ns_per_tick() {
  const auto c0 = std::chrono::steady_clock::now();
  const std::uint64_t t0 = StepProfile::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const std::uint64_t t1 = StepProfile::now();
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - c0).count();
  return ns / double(t1 - t0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"peg-throughput: training steps per second on a map, and where a step's time goes"};
  std::filesystem::path map = "maps/paper.yaml";
  long long steps = 2'000'000;
  int threads = 1;
  std::string config_source = "peg3d";
  std::vector<std::string> sets;
  bool breakdown = true, no_cache = false;
  std::string actions = "policies";
  int games = 256;
  app.add_option("--map", map, "the map")->capture_default_str();
  app.add_option("--steps", steps, "training steps per pass, over all threads")->capture_default_str()->check(CLI::Range(1LL, 1'000'000'000'000LL));
  app.add_option("--threads", threads, "threads, each with its own learners")->capture_default_str()->check(CLI::Range(1, 256));
  app.add_option("--config", config_source, "configuration: a preset (" + game::preset_list() + ") or a JSON file")->capture_default_str();
  app.add_option("--set", sets, "configuration overrides, key=value (repeatable)");
  app.add_flag("!--no-breakdown", breakdown, "skip the second pass that times each part of a step");
  app.add_flag("--no-cache", no_cache, "rebuild the world instead of using the on-disk cache");
  app.add_option("--actions", actions, "policies: the configuration's learners train; random: the vector env's env-only work")
      ->capture_default_str()->check(CLI::IsMember({"policies", "random"}));
  app.add_option("--games", games, "with --actions random: games stepped together")->capture_default_str()->check(CLI::Range(1, 65536));

  return cli::guarded_main(app, argc, argv, [&] {
    const game::GameConfig config = game::apply_game_overrides(game::load_game_config(config_source), sets, players::check_players);
    const auto build_start = std::chrono::steady_clock::now();
    const auto arena = cli::load_arena(map, !no_cache);
    const game::Sim sim(arena, config);
    const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
    // The movers' motion is simulated once per map, on demand; here all of it before the timed passes, so that
    // they time the steps alone (the simulation's cost is reported beside them).
    if (sim.movers() != nullptr) sim.movers()->simulate_all();
    const world::MapSpec& m = arena->map();
    const world::ArenaStats& stats = arena->stats();

    if (actions == "random") {
      const Pass p = run_random_batch(sim, steps, games, threads);
      nlohmann::ordered_json out{{"map", cli::resolve_input(map).string()}, {"actions", "random"}, {"games", games},
                                 {"threads", threads}, {"config", config_source}, {"steps", p.steps},
                                 {"seconds", p.seconds}, {"env_steps_per_s", double(p.steps) / p.seconds},
                                 {"agent_steps_per_s", double(p.agent_steps) / p.seconds}};
      std::puts(out.dump(2).c_str());
      return 0;
    }
    const Pass headline = run_pass(sim, steps, threads, false);
    nlohmann::ordered_json out{
        {"map", cli::resolve_input(map).string()},
        {"obstacles", m.spheres.size() + m.cylinders.size()},
        {"movers", m.movers.size()},
        {"triangles", stats.triangles},
        {"resolution_m", m.resolution},
        {"agents", m.scenarios.front().agents()},
        {"threads", threads},
        {"config", config_source},
        {"steps", headline.steps},
        {"episodes", headline.episodes},
        {"seconds", headline.seconds},
        {"env_steps_per_s", double(headline.steps) / headline.seconds},
        {"ns_per_step", headline.seconds * 1e9 / double(headline.steps)},
        {"agent_steps_per_s", double(headline.agent_steps) / headline.seconds},
        {"contact_give_ups", headline.contact_give_ups},
        {"world_build_s", build_s},
        {"world_cache", stats.cache_status}};
    if (const world::MoverTimeline* movers = sim.movers()) {
      const world::TimelineStats t = movers->stats();
      out["movers_timeline"] = {{"dynamic_bodies", t.dynamic_bodies}, {"keyframe_hz", t.keyframe_hz},
                                {"simulate_s", t.simulate_seconds}, {"mib", double(t.bytes) / 1048576.0},
                                {"worst_case_mib", double(t.worst_case_bytes) / 1048576.0}};
    }
    if (breakdown) {
      const double tick_ns = ns_per_tick();
      const Pass timed = run_pass(sim, steps, threads, true);
      // Per step of one thread: the parts' times are summed over threads, like the steps.
      const double per_step = 1.0 / double(timed.steps);
      nlohmann::ordered_json parts;
      double accounted = 0.0;
      for (int k = 0; k < StepProfile::kPartCount; ++k) {
        const double ns = double(timed.profile.ticks[std::size_t(k)]) * tick_ns * per_step;
        parts[StepProfile::name(StepProfile::Part(k))] = ns;
        accounted += ns;
      }
      const double timed_ns = timed.seconds * 1e9 * threads * per_step;
      parts["other"] = timed_ns - accounted;  // the play loop, captures, bookkeeping
      out["breakdown_ns_per_step"] = parts;
      out["breakdown_pass_ns_per_step"] = timed_ns;
    }
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    out["peak_rss_mib"] = double(usage.ru_maxrss) / 1024.0;
    std::puts(out.dump(2).c_str());
    return 0;
  });
}
