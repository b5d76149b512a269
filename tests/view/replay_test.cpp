// The replay data: base64 by the RFC's vectors, terrain simplified within its budget, and every recorded
// frame, event, mover pose and pair geometry of an episode as docs/viewer.md says, checked against the trace
// and the analytic Apollonius sphere and cone.
#include "view/replay.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "game/episode.hpp"
#include "world/map/map_loader.hpp"
#include "geometry/angles.hpp"
#include "test_arena.hpp"
#include "world_test_support.hpp"

namespace peg3d::view {
namespace {

std::vector<unsigned char> decoded(const std::string& s) {
  auto value = [](char c) -> unsigned {
    if (c >= 'A' && c <= 'Z') return unsigned(c - 'A');
    if (c >= 'a' && c <= 'z') return unsigned(c - 'a' + 26);
    if (c >= '0' && c <= '9') return unsigned(c - '0' + 52);
    return c == '+' ? 62u : 63u;
  };
  std::vector<unsigned char> out;
  for (std::size_t i = 0; i + 3 < s.size(); i += 4) {
    const unsigned v = value(s[i]) << 18 | value(s[i + 1]) << 12 | (s[i + 2] == '=' ? 0 : value(s[i + 2]) << 6) |
                       (s[i + 3] == '=' ? 0 : value(s[i + 3]));
    out.push_back((v >> 16) & 255);
    if (s[i + 2] != '=') out.push_back((v >> 8) & 255);
    if (s[i + 3] != '=') out.push_back(v & 255);
  }
  return out;
}

template <class T>
std::vector<T> series(const nlohmann::json& j) {
  const auto bytes = decoded(j.get<std::string>());
  EXPECT_EQ(bytes.size() % sizeof(T), 0u);
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

TEST(ViewBase64, MatchesTheRfc4648Vectors) {
  const auto b = [](const char* s) { return base64(s, std::strlen(s)); };
  EXPECT_EQ(b(""), "");
  EXPECT_EQ(b("f"), "Zg==");
  EXPECT_EQ(b("fo"), "Zm8=");
  EXPECT_EQ(b("foo"), "Zm9v");
  EXPECT_EQ(b("foob"), "Zm9vYg==");
  EXPECT_EQ(b("fooba"), "Zm9vYmE=");
  EXPECT_EQ(b("foobar"), "Zm9vYmFy");
  const unsigned char high[] = {0xfb, 0xff, 0xbf};
  EXPECT_EQ(base64(high, 3), "+/+/");
}

// A height field of n x n quads (2 n^2 triangles) over [0, n] x [0, n].
world::TriangleMesh hills(int n) {
  world::TriangleMesh m;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m.vertices.emplace_back(x, y, std::sin(0.3 * x) * std::cos(0.2 * y));
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  }
  return m;
}

TEST(ViewDrawnMesh, AMeshWithinTheBudgetIsDrawnWhole) {
  const world::TriangleMesh m = hills(10);
  const DrawnMesh d = drawn_mesh(m, 1000, "hills");
  EXPECT_EQ(d.source_triangles, 200u);
  EXPECT_EQ(d.triangle_count(), 200u);
  EXPECT_EQ(d.positions.size(), m.vertices.size() * 3);
}

TEST(ViewDrawnMesh, ALargeMeshIsSimplifiedWithinTheBudgetFromItsOwnVertices) {
  const world::TriangleMesh m = hills(100);  // 20 000 triangles
  const DrawnMesh d = drawn_mesh(m, 2000, "hills");
  EXPECT_EQ(d.source_triangles, 20000u);
  EXPECT_LE(d.triangle_count(), 2000u);
  EXPECT_GT(d.triangle_count(), 200u);  // simplified, not emptied
  const std::size_t vertices = d.positions.size() / 3;
  for (const std::uint32_t i : d.indices) ASSERT_LT(i, vertices);
  // Every drawn vertex is one of the mesh's (simplification collapses edges, it never invents points).
  for (std::size_t v = 0; v < vertices; ++v) {
    const double x = d.positions[3 * v], y = d.positions[3 * v + 1], z = d.positions[3 * v + 2];
    ASSERT_EQ(x, std::round(x));
    ASSERT_EQ(y, std::round(y));
    ASSERT_NEAR(z, std::sin(0.3 * x) * std::cos(0.2 * y), 1e-6);
  }
  // The corners of the field are kept: the drawn terrain spans the same area.
  float lo = 1e9f, hi = -1e9f;
  for (std::size_t v = 0; v < vertices; ++v) lo = std::min(lo, d.positions[3 * v]), hi = std::max(hi, d.positions[3 * v]);
  EXPECT_EQ(lo, 0.0f);
  EXPECT_EQ(hi, 100.0f);
}

// Pure pursuit against a fleeing evader on an open map with a mover: a short episode that ends in capture.
struct Episode {
  std::shared_ptr<const world::Arena> arena;
  game::GameConfig config;
  std::unique_ptr<game::Sim> sim;
  game::Trace trace;
};

Episode chase() {
  world::MapSpec m;
  m.name = "open";
  m.bounds = {Vec3::Zero(), Vec3(35, 35, 20)};
  m.resolution = 0.5;
  m.floor_is_obstacle = m.ceiling_is_obstacle = m.walls_is_obstacle = false;
  m.spheres.push_back({Vec3(30, 30, 5), 2.0});
  world::MoverSpec mover;
  mover.shape = {Shape::Kind::kBox, 1.0, 1.0, Vec3(1, 2, 3)};
  mover.motion = world::MoverSpec::Motion::kPath;
  mover.path = {{Vec3(3, 30, 15), Vec3(33, 30, 15)}, 2.0, false};
  m.movers.push_back(mover);
  m.scenarios.push_back(peg3d::testing::scenario("S", {5, 5, 10}, {12, 5, 10}));
  Episode e;
  e.arena = world::Arena::build(m);
  e.config = game::preset("peg3d");
  e.config.pursuer.policy = "pure-pursuit";
  e.config.evader.policy = "flee";
  e.config.pursuer.speed = 2.0;
  e.config.evader.speed = 1.0;
  e.sim = std::make_unique<game::Sim>(e.arena, e.config);
  peg3d::testing::play_once(*e.sim, e.arena->map().scenarios[0], 1, &e.trace);
  return e;
}

TEST(ViewReplay, HoldsEveryRecordedFrameOfEveryAgent) {
  const Episode e = chase();
  ASSERT_FALSE(e.trace.captures.empty());
  const ReplayScene scene(*e.arena);
  const nlohmann::json j = replay_json(scene, *e.sim, e.trace, {"title", "subtitle"});
  const int n = e.trace.frame_count();
  EXPECT_EQ(j.at("format"), "peg3d-replay");
  EXPECT_EQ(j.at("frames").get<int>(), n);
  EXPECT_EQ(series<double>(j.at("times_f64")), e.trace.times);
  ASSERT_EQ(j.at("agents").size(), 2u);
  EXPECT_EQ(j.at("agents")[0].at("name"), "pursuer_0");
  EXPECT_EQ(j.at("agents")[1].at("role"), "evader");
  EXPECT_EQ(j.at("agents")[0].at("speed").get<double>(), 2.0);
  for (int i = 0; i < 2; ++i) {
    const auto& track = j.at("agents")[std::size_t(i)].at("track");
    const auto pos = series<float>(track.at("position_f32"));
    const auto act = series<float>(track.at("action_f32"));
    const auto reward = series<float>(track.at("reward_f32"));
    const auto inputs = series<float>(track.at("inputs_f32"));
    const auto active = series<std::uint8_t>(track.at("active_u8"));
    ASSERT_EQ(pos.size(), std::size_t(3 * n));
    ASSERT_EQ(inputs.size(), std::size_t(6 * n));
    for (int k = 0; k < n; ++k) {
      const game::AgentFrame& f = e.trace.at(k, i);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(pos[std::size_t(3 * k + c)], float(f.state.position[c]));
      EXPECT_EQ(act[std::size_t(2 * k)], float(f.command.d_alpha));
      EXPECT_EQ(reward[std::size_t(k)], float(f.reward));
      EXPECT_EQ(inputs[std::size_t(6 * k)], float(f.percept.target_distance));
      EXPECT_EQ(active[std::size_t(k)], f.active ? 1 : 0);
    }
  }
  ASSERT_EQ(j.at("captures").size(), e.trace.captures.size());
  EXPECT_EQ(j.at("captures")[0].at("frame").get<int>(), e.trace.captures[0].step);
  EXPECT_EQ(j.at("capture_distance").get<double>(), e.config.capture_distance);
}

TEST(ViewReplay, SightCarriesEachFramesOpponentVisibilityAndEstimate) {
  // A ball between a pursuer with a 120 degree field of view and an evader fleeing behind it.
  world::MapSpec m = world::testing::empty_spec({35, 35, 20}, 0.5, 5.0);
  m.spheres.push_back({Vec3(10, 5, 10), 2.0});
  m.scenarios = {peg3d::testing::scenario("S", {5, 5, 10}, {15, 5, 10})};
  const auto arena = world::Arena::build(m);
  game::GameConfig c = game::preset("peg3d");
  c.pursuer.policy = "search";
  c.evader.policy = "flee";
  c.pursuer.sensors.sight.enabled = true;
  c.pursuer.sensors.sight.fov = 120.0;
  c.time_limit = 30.0;
  const game::Sim sim(arena, c);
  game::Trace trace;
  peg3d::testing::play_once(sim, m.scenarios[0], 1, &trace);
  const nlohmann::json j = replay_json(ReplayScene(*arena), sim, trace, {"title", "subtitle"});
  const int n = trace.frame_count();
  EXPECT_FALSE(j.at("agents")[1].contains("sight"));  // the evader has full information
  const auto& sight = j.at("agents")[0].at("sight");
  EXPECT_EQ(sight.at("fov").get<double>(), 120.0);
  const auto opponent = series<std::uint32_t>(sight.at("opponent_u32"));
  const auto visible = series<std::uint8_t>(sight.at("visible_u8"));
  const auto estimate = series<float>(sight.at("estimate_f32"));
  ASSERT_EQ(opponent.size(), std::size_t(n));
  ASSERT_EQ(estimate.size(), std::size_t(3 * n));
  int hidden = 0, seen = 0;
  for (int k = 0; k < n; ++k) {
    const game::AgentFrame& f = trace.at(k, 0);
    EXPECT_EQ(opponent[std::size_t(k)], 1u);
    EXPECT_EQ(visible[std::size_t(k)], f.sees ? 1 : 0);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(estimate[std::size_t(3 * k + a)], float(f.estimate[a]));
    // In sight the estimate is the evader as it is; hidden it is not.
    EXPECT_EQ(f.estimate == trace.at(k, 1).state.position, f.sees || k == 0) << "frame " << k;
    (f.sees ? seen : hidden) += 1;
  }
  EXPECT_GT(hidden, 0);
  EXPECT_GT(seen, 0);
}

TEST(ViewReplay, PairsCarryTheApolloniusSphereAndTheConeOfEq5) {
  const Episode e = chase();
  const nlohmann::json j = replay_json(ReplayScene(*e.arena), *e.sim, e.trace, {});
  ASSERT_EQ(j.at("pairs").size(), 1u);
  const auto sphere = series<float>(j.at("pairs")[0].at("apollonius_f32"));
  const auto cone = series<float>(j.at("pairs")[0].at("cone_f32"));
  // Frame 0: P = (5,5,10), E = (12,5,10), a = 1/2: centre (E - a^2 P) / (1 - a^2) = (14.333, 5, 10),
  // radius a / (1 - a^2) |PE| = 14 / 3.
  EXPECT_NEAR(sphere[0], 43.0 / 3.0, 1e-5);
  EXPECT_NEAR(sphere[1], 5.0, 1e-6);
  EXPECT_NEAR(sphere[3], 14.0 / 3.0, 1e-5);
  EXPECT_NEAR(cone[0], 1.0, 1e-6);  // the axis P->E
  EXPECT_NEAR(cone[3], std::asin(0.5), 1e-6);
}

TEST(ViewReplay, MoversAndPairsAreSampledWithinTheCapIncludingBothEnds) {
  const Episode e = chase();
  ReplaySettings s;
  s.max_pose_samples = 5;
  const nlohmann::json j = replay_json(ReplayScene(*e.arena, s), *e.sim, e.trace, {});
  const auto frames = series<std::uint32_t>(j.at("pose_frames_u32"));
  const int n = e.trace.frame_count();
  ASSERT_GT(n, 5);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_EQ(frames.front(), 0u);
  EXPECT_EQ(frames.back(), std::uint32_t(n - 1));
  const auto poses = series<float>(j.at("movers")[0].at("poses_f32"));
  ASSERT_EQ(poses.size(), 5u * 7u);
  EXPECT_EQ(j.at("movers")[0].at("shape"), "box");
  for (std::size_t s_i = 0; s_i < 5; ++s_i) {
    const Pose p = e.sim->movers()->pose(0, e.trace.times[frames[s_i]]);
    EXPECT_EQ(poses[7 * s_i], float(p.position.x()));  // 2 m/s along x from x = 3
    EXPECT_NEAR(poses[7 * s_i], 3.0 + 2.0 * e.trace.times[frames[s_i]], 1e-5);
  }
  EXPECT_EQ(series<float>(j.at("pairs")[0].at("apollonius_f32")).size(), 5u * 4u);
}

TEST(ViewReplayScene, HoldsTheMapsObstaclesAndItsTerrainInWorldCoordinates) {
  world::MapSpec m = world::testing::empty_spec(Vec3(8, 6, 5), 0.25, 2.0);
  m.spheres.push_back({Vec3(2, 2, 2), 0.8});
  m.cylinders.push_back({Vec3(6, 4, 0), 0.5, 3.0});
  m.meshes.push_back(world::testing::mesh_entry("wall.obj", Vec3(4, 3, 0), 0.4));
  const auto arena = world::testing::build(m);
  const ReplayScene scene(*arena);
  const nlohmann::json& j = scene.json();
  EXPECT_EQ(j.at("spheres")[0].at("radius").get<double>(), 0.8);
  EXPECT_EQ(j.at("cylinders")[0].at("height").get<double>(), 3.0);
  ASSERT_EQ(j.at("meshes").size(), 1u);
  EXPECT_EQ(j.at("meshes")[0].at("name"), "wall.obj");
  EXPECT_EQ(j.at("meshes")[0].at("drawn_triangles").get<std::size_t>(), arena->meshes()[0].triangle_count());
  const auto positions = series<float>(j.at("meshes")[0].at("positions_f32"));
  ASSERT_EQ(positions.size(), arena->meshes()[0].vertices.size() * 3);
  EXPECT_EQ(positions[0], float(arena->meshes()[0].vertices[0].x()));
  EXPECT_EQ(scene.drawn_triangles(), arena->meshes()[0].triangle_count());
}

}  // namespace
}  // namespace peg3d::view

namespace peg3d::view {
namespace {

// Push mode: the run moved the bodies itself, so the replay draws them from the trace (the crate pushed along
// +x by the pursuer), not from the shared timeline (where it would stand at its start).
TEST(ViewReplay, PushModeBodiesMoveAsTheRunPushedThem) {
  const auto arena = world::Arena::build(
      world::load_map(std::string(PEG3D_SOURCE_DIR) + "/tests/collision/maps/push.yaml"));
  game::GameConfig c = game::preset("peg3d");
  c.mover_dynamics = game::MoverDynamics::kPush;
  c.collision = game::CollisionMode::kPenalize;
  c.pursuer.guard.enabled = c.evader.guard.enabled = false;
  c.pursuer.motion_space = false;
  c.evader.speed = 0.0;
  c.time_limit = 8.0;
  const game::Sim sim(arena, c);
  game::SimState st(sim);
  game::reset(sim, st, *arena->map().find_scenario("crate-lane"), 1);
  game::Trace trace;
  trace.record(st, false);
  const std::array<Steering, 2> straight{};
  while (!st.done) {
    game::step(sim, st, straight);
    trace.record(st, true);
  }
  ASSERT_EQ(trace.movers, 3);
  const nlohmann::json j = replay_json(ReplayScene(*arena), sim, trace, {});
  const auto poses = series<float>(j.at("movers")[1].at("poses_f32"));
  ASSERT_GE(poses.size(), 14u);
  EXPECT_NEAR(poses[0], 8.0, 0.05);                  // the crate starts at x = 8
  EXPECT_GT(poses[poses.size() - 7], 11.0);         // and ends pushed ahead of the pursuer
  EXPECT_NEAR(series<float>(j.at("movers")[2].at("poses_f32")).back(), 1.0, 0.05);  // the solid crate's w stays ~1
}

}  // namespace
}  // namespace peg3d::view
