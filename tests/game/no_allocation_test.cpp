// The step loop allocates nothing: whole training and evaluation episodes (observe, act, steer, move, sweep,
// reward, learn) run without a single operator new once the game and its policies exist. This test program
// replaces the global operator new with a counting one, so it is a target of its own.

#include <gtest/gtest.h>

#include "../support/counting_new.hpp"
#include "core/random.hpp"
#include "game/episode.hpp"
#include "world/map_spec.hpp"

namespace peg3d::game {
namespace {

TEST(GameNoAllocation, TrainingAndEvaluationEpisodes) {
  const auto arena = world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/maps/paper.yaml"));
  for (const char* name : {"peg3d", "paper", "baseline"}) {
    const GameConfig c = preset(name);
    Game game(arena, c);
    auto p = make_policy(c.pursuer, Role::kPursuer, 1);
    auto e = make_policy(c.evader, Role::kEvader, 2);
    const auto& scenarios = arena->map().scenarios;
    game.play(scenarios[0], *p, *e, true, 0);  // warm-up: anything lazily created is created now
    std::vector<StepRecord> trace;
    trace.reserve(c.max_steps() + 1);
    const long before = testing::g_allocations.load();
    long steps = 0;
    for (std::uint64_t k = 0; k < 8; ++k) {
      steps += game.play(scenarios[k % scenarios.size()], *p, *e, true, derive_seed(3, {k})).steps;
    }
    steps += game.play(scenarios[1], *p, *e, false, 4).steps;
    trace.clear();
    steps += game.play(scenarios[2], *p, *e, false, 5, &trace).steps;
    EXPECT_EQ(testing::g_allocations.load() - before, 0) << name << ": allocations over " << steps << " steps";
    EXPECT_GT(steps, 1000) << name;
  }
}

}  // namespace
}  // namespace peg3d::game
