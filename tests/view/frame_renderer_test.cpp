// Images of a game (view/frame_renderer.hpp): the camera's projection, agents in their roles' colours where
// the camera sees them, occlusion by an obstacle in front, the floor and the sky, movers where they are at the
// state's time, and frames that depend on the state alone.
#include "view/frame_renderer.hpp"

#include <gtest/gtest.h>

#include <random>

#include "game/episode.hpp"
#include "test_arena.hpp"
#include "world/map/map_loader.hpp"

namespace peg3d::view {
namespace {

const Vec3 kSize(35, 35, 20);

struct Pixel {
  int r, g, b;
};

Pixel pixel_at(const std::vector<std::uint8_t>& rgb, const FrameRenderer& f, const Vec3& p) {
  const Vec3 s = f.project(p);
  const int x = int(s.x()), y = int(s.y());
  EXPECT_TRUE(x >= 0 && x < f.width() && y >= 0 && y < f.height()) << p.transpose() << " projects off the image";
  const std::size_t k = 3 * (std::size_t(std::clamp(y, 0, f.height() - 1)) * std::size_t(f.width()) +
                             std::size_t(std::clamp(x, 0, f.width() - 1)));
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

// The colour's hue, shaded: the palette entry scaled by a light factor in [0.45, 1].
bool shaded(const Pixel& p, const std::uint8_t (&c)[3]) {
  const double s = double(p.r + p.g + p.b) / double(c[0] + c[1] + c[2]);
  if (s < 0.44 || s > 1.01) return false;
  return std::abs(p.r - c[0] * s) <= 3 && std::abs(p.g - c[1] * s) <= 3 && std::abs(p.b - c[2] * s) <= 3;
}

struct Game {
  std::shared_ptr<const world::Arena> arena;
  game::Sim sim;
  game::SimState state;
  world::Scenario scenario;
  Game(std::vector<world::SphereObstacle> spheres, const Vec3& pursuer, const Vec3& evader)
      : arena(testing::make_arena(kSize, std::move(spheres), {testing::scenario("s", pursuer, evader)})),
        sim(arena, game::preset("peg3d")),
        state(sim),
        scenario(arena->map().scenarios.front()) {
    game::reset(sim, state, scenario, 1);
  }
};

TEST(ViewFrameRenderer, TheArenasCentreProjectsToTheImagesCentre) {
  const Game g({}, {5, 5, 5}, {30, 30, 5});
  const FrameRenderer f(g.sim);
  const Vec3 c = f.project(0.5 * kSize);
  EXPECT_NEAR(c.x(), 320.0, 1e-9);
  EXPECT_NEAR(c.y(), 240.0, 1e-9);
  EXPECT_GT(c.z(), 0.0);
  // Every corner of the arena's box is in view.
  for (int k = 0; k < 8; ++k) {
    const Vec3 s = f.project(Vec3(k & 1 ? kSize.x() : 0, k & 2 ? kSize.y() : 0, k & 4 ? kSize.z() : 0));
    EXPECT_TRUE(s.z() > 0 && s.x() >= 0 && s.x() < 640 && s.y() >= 0 && s.y() < 480) << "corner " << k;
  }
}

TEST(ViewFrameRenderer, EachAgentShowsInItsRolesColourWhereTheCameraSeesIt) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(3, 32), z(2, 18);
  for (int trial = 0; trial < 6; ++trial) {
    const Vec3 p(x(rng), x(rng), z(rng)), e(x(rng), x(rng), z(rng));
    if ((p - e).norm() < 3.0) continue;
    Game g({}, p, e);
    FrameRenderer f(g.sim);
    std::vector<std::uint8_t> rgb(640 * 480 * 3);
    f.render(g.state, rgb);
    SCOPED_TRACE("trial " + std::to_string(trial));
    // The nearer one may hide the other: check the one whose projected centre is nearer the camera first.
    const bool p_first = f.project(p).z() < f.project(e).z();
    EXPECT_TRUE(shaded(pixel_at(rgb, f, p_first ? p : e), p_first ? FramePalette::kPursuer : FramePalette::kEvader));
    const Vec3 sp = f.project(p), se = f.project(e);
    if (std::hypot(sp.x() - se.x(), sp.y() - se.y()) > 20.0) {
      EXPECT_TRUE(shaded(pixel_at(rgb, f, p_first ? e : p), p_first ? FramePalette::kEvader : FramePalette::kPursuer));
    }
  }
}

TEST(ViewFrameRenderer, AnObstacleInFrontHidesTheAgentBehindIt) {
  const Vec3 agent(20, 22, 6);
  Game open({}, agent, {5, 5, 5});
  FrameRenderer probe(open.sim);
  // A ball of 1.5 m on the line from the camera to the agent, 6 m in front of it.
  const Vec3 rock = agent + 6.0 * (probe.eye() - agent).normalized();
  Game hidden({{rock, 1.5}}, agent, {5, 5, 5});
  std::vector<std::uint8_t> a(640 * 480 * 3), b(a.size());
  FrameRenderer fa(open.sim), fb(hidden.sim);
  fa.render(open.state, a);
  fb.render(hidden.state, b);
  EXPECT_TRUE(shaded(pixel_at(a, fa, agent), FramePalette::kPursuer));
  EXPECT_TRUE(shaded(pixel_at(b, fb, agent), FramePalette::kObstacle));
}

TEST(ViewFrameRenderer, TheFloorIsGreyAndTheSkyIsAbove) {
  Game g({}, {5, 30, 10}, {30, 30, 10});
  FrameRenderer f(g.sim);
  std::vector<std::uint8_t> rgb(640 * 480 * 3);
  f.render(g.state, rgb);
  const Pixel floor = pixel_at(rgb, f, {17.3, 12.4, 0.0});
  EXPECT_NEAR(floor.r, floor.g, 6);
  EXPECT_NEAR(floor.g, floor.b, 8);
  EXPECT_GT(floor.r, 70);
  const Pixel sky{rgb[3 * 5], rgb[3 * 5 + 1], rgb[3 * 5 + 2]};  // the top row
  EXPECT_GT(sky.b, sky.r + 100);
  EXPECT_GT(sky.b, 220);
}

TEST(ViewFrameRenderer, MoversAreDrawnWhereTheyAreAtTheStatesTime) {
  const auto arena = world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/maps/patrol.yaml"));
  const game::Sim sim(arena, game::preset("peg3d"));
  game::SimState state(sim);
  game::reset(sim, state, arena->map().scenarios.front(), 3);
  FrameRenderer f(sim);
  std::vector<std::uint8_t> rgb(640 * 480 * 3);
  const std::vector<Steering> still(state.agents.size());
  for (int k = 0; k < 60; ++k) {
    if (k % 20 == 0) {
      f.render(state, rgb);
      // The sphere orbiting the centre (mover 3): its centre's pixel, unless an agent or another mover is nearer.
      const Vec3 at = sim.movers()->pose(3, state.time).position;
      SCOPED_TRACE("t = " + std::to_string(state.time));
      EXPECT_TRUE(shaded(pixel_at(rgb, f, at), FramePalette::kMover));
    }
    game::step(sim, state, still);
  }
}

TEST(ViewFrameRenderer, AFrameDependsOnTheStateAlone) {
  Game g({{{17, 17, 8}, 2.0}}, {5, 5, 5}, {30, 30, 15});
  FrameRenderer f(g.sim);
  std::vector<std::uint8_t> first(640 * 480 * 3), again(first.size()), moved(first.size());
  f.render(g.state, first);
  const std::vector<Steering> still(2);
  game::SimState other(g.sim);
  game::reset(g.sim, other, g.scenario, 1);
  for (int k = 0; k < 30; ++k) game::step(g.sim, other, still);
  f.render(other, moved);
  f.render(g.state, again);
  EXPECT_EQ(first, again);
  EXPECT_NE(first, moved);
}

}  // namespace
}  // namespace peg3d::view
