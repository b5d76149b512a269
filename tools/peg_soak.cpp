// peg-soak: the training loop run for a very long time in one process, watching its memory. One set of FACL
// learners (both roles) trains on every scenario of the map in turn, as peg-bench-game's training steps do,
// without keeping learning curves (those grow by design). Prints CSV rows of episodes, seconds, resident
// memory and game steps at --samples points, then a line comparing memory after warm-up with the end.
//   build/bin/peg-soak --map maps/paper.yaml --episodes 1000000 > soak.csv

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli_common.hpp"
#include "core/random.hpp"
#include "game/episode.hpp"
#include "players/lineup.hpp"
#include "world/arena.hpp"

namespace {

using namespace peg3d;

// Resident memory of this process, KiB (VmRSS of /proc/self/status).
long resident_kib() {
  long kib = -1;
  if (FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, f) != nullptr) {
      if (std::sscanf(line, "VmRSS: %ld kB", &kib) == 1) break;
    }
    std::fclose(f);
  }
  return kib;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Trains FACL agents for many episodes in one process and reports its memory over time"};
  std::filesystem::path map = "maps/paper.yaml";
  std::string preset = "peg3d";
  long long episodes = 100000;
  int samples = 50;
  double warmup = 0.1;
  std::uint64_t seed = 1;
  app.add_option("--map", map, "map to train on (every scenario in turn)");
  app.add_option("--config", preset, "configuration preset")->check(CLI::IsMember(std::vector<std::string>(std::begin(game::kPresetNames), std::end(game::kPresetNames))));
  app.add_option("--episodes", episodes, "training episodes")->check(CLI::Range(1LL, 1000000000LL));
  app.add_option("--samples", samples, "memory samples printed")->check(CLI::Range(2, 100000));
  app.add_option("--warmup", warmup, "fraction of the episodes after which memory must stay flat")->check(CLI::Range(0.0, 0.9));
  app.add_option("--seed", seed, "root seed");
  return cli::guarded_main(app, argc, argv, [&] {
    const auto arena = cli::load_arena(cli::resolve_input(map), /*use_cache=*/true);
    const game::GameConfig config = game::preset(preset);
    const game::Sim sim(arena, config);
    game::SimState state(sim);
    const auto& scenarios = arena->map().scenarios;
    players::Lineup lineup;
    players::add_configured(lineup, config, game::Role::kPursuer, int(scenarios[0].pursuers.size()), derive_seed(seed, {1}));
    players::add_configured(lineup, config, game::Role::kEvader, int(scenarios[0].evaders.size()), derive_seed(seed, {2}));
    const auto start = std::chrono::steady_clock::now();
    long long steps = 0, captures = 0;
    long warm_kib = -1, peak_after_warmup = 0;
    std::printf("episodes,seconds,rss_kib,steps,captures\n");
    for (long long e = 1; e <= episodes; ++e) {
      const world::Scenario& s = scenarios[std::size_t(e % static_cast<long long>(scenarios.size()))];
      const game::EpisodeResult r = game::play(sim, state, s, lineup.policies(), /*learning=*/true, derive_seed(seed, {3, std::uint64_t(e)}));
      steps += r.steps;
      captures += r.captured();
      const bool sample = e % std::max(1LL, episodes / samples) == 0 || e == episodes;
      if (!sample) continue;
      const long kib = resident_kib();
      if (e >= static_cast<long long>(warmup * double(episodes))) {
        if (warm_kib < 0) warm_kib = kib;
        peak_after_warmup = std::max(peak_after_warmup, kib);
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("%lld,%.1f,%ld,%lld,%lld\n", e, seconds, kib, steps, captures);
      std::fflush(stdout);
    }
    std::fprintf(stderr, "%s: %lld episodes, %lld steps; resident memory %ld KiB after warm-up, %ld KiB at most after it (%+ld KiB)\n",
                 map.string().c_str(), episodes, steps, warm_kib, peak_after_warmup, peak_after_warmup - warm_kib);
    return 0;
  });
}
