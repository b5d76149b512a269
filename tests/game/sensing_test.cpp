// Range sensors in the game (game/sensing.hpp, SimState::sensing): readings against analytic distances, and against
// testing every solid, mover, pushed body and agent at the instant of each scan over whole games, for the lidar and
// the depth camera; scans only when their period comes; maps and observations fed from them; a lidar that only
// observes changes nothing of the game; the same readings for a seed on any thread count (golden hashes).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "core/hash.hpp"
#include "core/random.hpp"
#include "game/episode.hpp"
#include "game/observation.hpp"
#include "game/sensing.hpp"
#include "sense/depth_camera.hpp"
#include "sense/lidar.hpp"
#include "support/sanitized.hpp"
#include "test_arena.hpp"
#include "world/map/map_loader.hpp"

namespace peg3d::game {
namespace {

sense::LidarConfig lidar(int azimuth, int elevation, double fov_elevation, double range) {
  sense::LidarConfig c;
  c.azimuth_rays = azimuth;
  c.elevation_rays = elevation;
  c.elevation_fov = fov_elevation;
  c.range = range;
  return c;
}

// Agent i's lidar readings and echoes (empty without a lidar), and the lidar of an agent.
std::span<const double> lidar_ranges(const SimState& st, int i) {
  const sense::Reading* r = st.reading(i, "lidar");
  return r != nullptr ? r->values : std::span<const double>{};
}
std::span<const std::uint8_t> lidar_echoes(const SimState& st, int i) {
  const sense::Reading* r = st.reading(i, "lidar");
  return r != nullptr ? r->echo : std::span<const std::uint8_t>{};
}
const sense::Lidar* lidar_of(const Sim& sim, Role role, int rank) {
  return dynamic_cast<const sense::Lidar*>(sim.sensor(role, rank, "lidar"));
}

// One arena per map for the whole program: quarry's movers are simulated once for every test here.
std::shared_ptr<const world::Arena> map_arena(const std::string& map) {
  static std::map<std::string, std::shared_ptr<const world::Arena>> built;
  auto& arena = built[map];
  if (!arena) arena = world::Arena::build(world::load_map(std::string(PEG3D_SOURCE_DIR) + "/" + map));
  return arena;
}

// What `rays` of agent i meet now within `range`, by testing every static solid, mover, pushed body and (when the
// sensor sees them) other agent.
std::vector<sense::RayHit> reference_hits(const Sim& sim, const SimState& st, int i, std::span<const Ray> rays,
                                          double range, bool sees_agents) {
  std::vector<sense::RayHit> out;
  for (const Ray& ray : rays) {
    sense::RayHit want = sense::cast_every_solid(sim.arena(), ray, range);
    if (sim.movers() != nullptr) {
      const world::MoverHit m = sim.movers()->first_along_scan(ray, st.time, want.distance);
      if (m.mover >= 0 && m.distance < want.distance) want = {m.distance, sense::RayTarget::kMover, m.mover};
    }
    if (st.push) {
      for (int m = 0; m < st.push->movers(); ++m) {
        const world::MoverSpec& spec = sim.arena().map().movers[std::size_t(m)];
        if (spec.kinematic()) continue;
        const auto d = ray_shape(ray, spec.shape, st.push->pose(m), want.distance);
        if (d && *d < want.distance) want = {*d, sense::RayTarget::kMover, m};
      }
    }
    for (int j = 0; j < st.agent_count() && sees_agents; ++j) {
      const AgentState& b = st.agents[std::size_t(j)];
      if (j == i || !b.active) continue;
      const auto d = ray_sphere(ray, b.kinematics.position, b.config->radius, want.distance);
      if (d && *d < want.distance) want = {*d, sense::RayTarget::kBall, j};
    }
    out.push_back(want);
  }
  return out;
}

// What agent i's lidar rays meet now.
std::vector<sense::RayHit> reference(const Sim& sim, const SimState& st, int i) {
  const AgentState& a = st.agents[std::size_t(i)];
  const sense::Lidar& l = *lidar_of(sim, a.role, a.rank);
  std::vector<Ray> rays(std::size_t(l.rays()));
  l.rays_at(a.kinematics.position, a.kinematics.heading, rays);
  return reference_hits(sim, st, i, rays, l.config().range, l.config().sees_agents);
}

// Agent i's readings equal the reference's (no noise, no dropout); returns how many rays returned an echo.
int expect_readings_match(const Sim& sim, const SimState& st, int i) {
  const auto want = reference(sim, st, i);
  const auto ranges = lidar_ranges(st, i);
  const auto echo = lidar_echoes(st, i);
  const double range = lidar_of(sim, st.agents[std::size_t(i)].role, st.agents[std::size_t(i)].rank)->config().range;
  EXPECT_EQ(ranges.size(), want.size());
  int echoes = 0;
  for (std::size_t k = 0; k < want.size(); ++k) {
    const bool met = want[k].target != sense::RayTarget::kNone;
    EXPECT_EQ(echo[k], met ? 1 : 0) << "step " << st.step << " agent " << i << " ray " << k;
    EXPECT_NEAR(ranges[k], met ? want[k].distance : range, 1e-9) << "step " << st.step << " agent " << i << " ray " << k;
    echoes += met;
  }
  return echoes;
}

TEST(Scans, ARayAlongTheHeadingReadsTheDistanceToTheSphereAhead) {
  Rng rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 at(10 + 2 * u(rng), 10 + 2 * u(rng), 10 + 2 * u(rng));
    // Any azimuth, climbing or diving up to 10 degrees (within the steering's climb limit, so a zero command keeps it).
    const double azimuth = 2 * kPi * u(rng), elevation = (u(rng) - 0.5) * 20.0 * kPi / 180.0;
    const Vec3 d = direction(Heading{azimuth, kPi / 2 - elevation});
    const double gap = 2.0 + 5.0 * u(rng), radius = 0.3 + 1.5 * u(rng);
    world::Scenario s = testing::scenario("s", at, Vec3(1.5, 1.5, 1.5));
    s.pursuers[0].heading = heading_of(d);
    const auto arena = testing::make_arena(Vec3(22, 22, 22), {{at + (gap + radius) * d, radius}}, {s});
    GameConfig c = preset("peg3d");
    c.pursuer.sensors.lidar = lidar(1, 1, 0.0, 9.0);
    c.pursuer.guard.enabled = false;
    c.pursuer.motion_space = false;  // a zero command keeps the heading
    const Sim sim(arena, c);
    SimState st(sim);
    reset(sim, st, s, 1);
    ASSERT_EQ(lidar_ranges(st, 0).size(), 1u);
    EXPECT_NEAR(lidar_ranges(st, 0)[0], gap, 1e-9);
    EXPECT_EQ(lidar_echoes(st, 0)[0], 1);
    EXPECT_TRUE(lidar_ranges(st, 1).empty());  // the evader has no lidar
    // One step straight on: the pursuer is speed * dt nearer (it reads from where the step left it).
    const std::array<Steering, 2> none{};
    step(sim, st, none);
    EXPECT_NEAR(lidar_ranges(st, 0)[0], gap - c.pursuer.speed * c.dt, 1e-9);
  }
}

// The pursuer at (5, 10, 10) heading +x, the evader 7 m ahead at (12, 10, 10), in a 30 x 20 x 20 m room whose faces
// are no obstacles.
struct FacingEvader {
  world::Scenario s = facing();
  std::shared_ptr<const world::Arena> arena = testing::make_arena(Vec3(30, 20, 20), {}, {s});
  const Vec3 e{12, 10, 10};
  static world::Scenario facing() {
    world::Scenario s = testing::scenario("s", Vec3(5, 10, 10), Vec3(12, 10, 10));
    s.pursuers[0].heading = Heading{0.0, kPi / 2};
    return s;
  }
};

TEST(Scans, AgentsAreSeenUnlessTheSettingSaysOtherwise) {
  const auto [s, arena, e] = FacingEvader{};
  for (const bool sees : {true, false}) {
    GameConfig c = preset("peg3d");
    c.pursuer.sensors.lidar = lidar(1, 1, 0.0, 20.0);
    c.pursuer.sensors.lidar.sees_agents = sees;
    const Sim sim(arena, c);
    SimState st(sim);
    reset(sim, st, s, 1);
    if (sees) {
      EXPECT_NEAR(lidar_ranges(st, 0)[0], 7.0 - c.evader.radius, 1e-12);
    } else {
      EXPECT_EQ(lidar_echoes(st, 0)[0], 0);  // the arena's faces are not obstacles on this map
      EXPECT_EQ(lidar_ranges(st, 0)[0], 20.0);
    }
  }
}

TEST(Scans, AnAgentsMapLeavesOutTheOtherAgentsUnlessTheSettingSaysOtherwise) {
  // The pursuer's rays fan out across the evader 7 m ahead, in a room whose faces are no obstacles: every echo
  // is the evader's.
  const auto [s, arena, e] = FacingEvader{};
  for (const bool insert : {false, true}) {
    GameConfig c = preset("peg3d");
    c.pursuer.sensors.lidar = lidar(9, 5, 8.0, 20.0);
    c.pursuer.sensors.lidar.azimuth_fov = 8.0;
    c.pursuer.map.enabled = true;
    c.pursuer.map.insert_agents = insert;
    const Sim sim(arena, c);
    SimState st(sim);
    reset(sim, st, s, 1);
    int echoes = 0;
    for (const std::uint8_t k : lidar_echoes(st, 0)) echoes += k;
    EXPECT_GT(echoes, 0);  // the readings see the evader either way
    EXPECT_LT(echoes, 45);
    const sense::ScanMap& map = *st.map(0);
    const sense::OccupiedPoint near = map.nearest_occupied(e, 1.0);
    EXPECT_GT(map.known_cells(), 0);  // the rays that met nothing carve free space
    if (insert) {
      EXPECT_TRUE(near.found);
      EXPECT_LT(near.distance, c.evader.radius);
    } else {
      EXPECT_EQ(map.occupied_cells(), 0);
    }
  }
}

// Random steering for a whole game, checking every scan against the reference.
void check_game(const char* map, MoverDynamics dynamics, int steps, int min_echoes_on_movers, std::size_t scenarios = 99) {
  const auto arena = map_arena(map);
  GameConfig c = preset("peg3d");
  c.mover_dynamics = dynamics;
  c.collision = CollisionMode::kPenalize;
  c.pursuer.sensors.lidar = lidar(16, 3, 50.0, 15.0);
  c.evader.sensors.lidar = lidar(8, 2, 20.0, 8.0);
  c.evader.sensors.lidar.period = 3;
  const Sim sim(arena, c);
  SimState st(sim);
  Rng rng(8);
  int checked = 0, echoes = 0, on_movers = 0;
  const auto& all = arena->map().scenarios;
  for (std::size_t k = 0; k < std::min(scenarios, all.size()); ++k) {
    reset(sim, st, all[k], 2);
    for (int i = 0; i < st.agent_count(); ++i) echoes += expect_readings_match(sim, st, i), ++checked;
    std::vector<Steering> u(std::size_t(st.agent_count()));
    for (int k = 0; k < steps && !st.done; ++k) {
      for (Steering& s_ : u) s_ = {uniform(rng, -0.3, 0.3), uniform(rng, -0.2, 0.2)};
      const StepEvents& ev = step(sim, st, u);
      for (int i = 0; i < st.agent_count(); ++i) {
        const int period = st.agents[std::size_t(i)].role == Role::kPursuer ? 1 : 3;
        const bool due = ev.agents[std::size_t(i)].acted && st.step % period == 0;
        EXPECT_EQ(st.reading(i, "lidar")->step == st.step, due) << "step " << st.step << " agent " << i;
        if (!due) continue;
        echoes += expect_readings_match(sim, st, i), ++checked;
        if (::testing::Test::HasFailure()) return;
        for (const sense::RayHit& h : reference(sim, st, i)) on_movers += h.target == sense::RayTarget::kMover;
      }
    }
  }
  std::printf("%s: %d scans checked, %d echoes, %d on movers\n", map, checked, echoes, on_movers);
  EXPECT_GT(checked, 60);
  EXPECT_GT(echoes, 1000);
  EXPECT_GE(on_movers, min_echoes_on_movers);
}

TEST(Scans, ReadingsEqualTestingEverySolidAndAgentOnForest) { check_game("maps/forest.yaml", MoverDynamics::kShared, 150, 0); }

// Under the sanitizers the quarry games below play one scenario (support/sanitized.hpp).
TEST(Scans, ReadingsEqualTestingEveryMoverAtTheInstantOfTheScanOnQuarry) {
  check_game("maps/quarry.yaml", MoverDynamics::kShared, 60, 50, peg3d::testing::release_or_sanitized(99, 1));
}

TEST(Scans, ReadingsSeeTheBodiesWhereThePushModeRunMovedThem) {
  check_game("maps/quarry.yaml", MoverDynamics::kPush, peg3d::testing::release_or_sanitized(40, 50), 20,
             peg3d::testing::release_or_sanitized(2, 1));
}

TEST(Scans, ALidarThatOnlyObservesChangesNothingOfTheGame) {
  const auto arena = map_arena("maps/forest.yaml");
  GameConfig with = preset("peg3d");
  with.pursuer.sensors.lidar = lidar(32, 2, 30.0, 10.0);
  with.evader.sensors.lidar = with.pursuer.sensors.lidar;
  with.evader.sensors.lidar.noise = 0.05;
  const Sim plain(arena, preset("peg3d")), sensing(arena, with);
  for (const world::Scenario& s : arena->map().scenarios) {
    Trace a, b;
    const EpisodeResult ra = testing::play_once(plain, s, 7, &a), rb = testing::play_once(sensing, s, 7, &b);
    ASSERT_EQ(a.frame_count(), b.frame_count()) << s.name;
    EXPECT_EQ(ra.steps, rb.steps);
    for (int f = 0; f < a.frame_count(); ++f) {
      for (int i = 0; i < s.agents(); ++i) ASSERT_EQ(a.at(f, i).state.position, b.at(f, i).state.position) << s.name;
    }
  }
}

// A configuration whose agents sense obstacles through their own maps, built from 64-ray lidars.
GameConfig own_map_config() {
  GameConfig c = preset("peg3d");
  for (AgentConfig* a : {&c.pursuer, &c.evader}) {
    a->sensors.lidar = lidar(16, 4, 60.0, 10.0);
    a->map.enabled = true;
    a->observation.obstacles = ObstacleSource::kOwnMap;
  }
  return c;
}

TEST(Scans, OwnMapInputsAreTheNearestOccupiedCellOfTheMapTheScansBuilt) {
  const auto arena = map_arena("maps/forest.yaml");
  const Sim sim(arena, own_map_config());
  SimState st(sim);
  Rng rng(4);
  const world::Scenario& s = arena->map().scenarios.front();
  reset(sim, st, s, 3);
  // A map of the agent's own, fed the same scans from the readings, beside the state's.
  sense::ScanMap mine(sim.config().pursuer.map, arena->bounds().lo, arena->bounds().hi);
  std::vector<Ray> rays(64);
  std::vector<Vec3> points(64);
  int found = 0;
  std::vector<Steering> u(2);
  for (int k = 0; k < 200 && !st.done; ++k) {
    const AgentState& a = st.agents[0];
    lidar_of(sim, Role::kPursuer, 0)->rays_at(a.kinematics.position, a.kinematics.heading, rays);
    for (std::size_t r = 0; r < rays.size(); ++r) {
      const double d = lidar_echoes(st, 0)[r] != 0 ? lidar_ranges(st, 0)[r] : 10.0 + 0.5;
      points[r] = a.kinematics.position + d * rays[r].direction;
    }
    mine.insert(a.kinematics.position, points, 10.0);
    ASSERT_EQ(st.map(0)->known_cells(), mine.known_cells()) << "step " << st.step;
    ASSERT_EQ(st.map(0)->occupied_cells(), mine.occupied_cells()) << "step " << st.step;
    const sense::OccupiedPoint want = mine.nearest_occupied(a.kinematics.position, arena->max_distance());
    const ObstacleSense& got = observe(st, 0).field;
    ASSERT_EQ(got.found, want.found) << "step " << st.step;
    ASSERT_EQ(got.distance, want.distance) << "step " << st.step;
    found += got.found;
    for (Steering& c : u) c = {uniform(rng, -0.3, 0.3), uniform(rng, -0.2, 0.2)};
    step(sim, st, u);
  }
  EXPECT_GT(found, 20);
  // The next episode starts from an empty map: after the reset's scan it knows only what that scan saw.
  reset(sim, st, s, 4);
  EXPECT_LT(st.map(0)->known_cells(), mine.known_cells() / 4);
}

TEST(Scans, TheRepulsionOfAnOwnMapAgentRewardsItsMoveNotWhatItsScanRevealed) {
  // In one map, d_O moves by at most the step's length (a distance is 1-Lipschitz, and so is its minimum with the
  // faces' and the cap), so the term 1 - exp(-alpha_r (d_after - d_before)) is at least 1 - exp(alpha_r v dt). A
  // scan that reveals a nearer cell must not count: d_before is measured again in the map it left.
  const auto arena = map_arena("maps/forest.yaml");
  const GameConfig c = own_map_config();
  const Sim sim(arena, c);
  SimState st(sim);
  Rng rng(6);
  std::vector<Steering> u(2);
  int scanned = 0, revealed = 0;
  for (const world::Scenario& s : arena->map().scenarios) {
    reset(sim, st, s, 11);
    for (int k = 0; k < 150 && !st.done; ++k) {
      std::array<double, 2> seen_before{};
      for (int i = 0; i < 2; ++i) seen_before[std::size_t(i)] = st.agents[std::size_t(i)].view.percept.obstacle.distance;
      for (Steering& cmd : u) cmd = {uniform(rng, -0.3, 0.3), uniform(rng, -0.2, 0.2)};
      step(sim, st, u);
      for (int i = 0; i < 2; ++i) {
        const AgentState& a = st.agents[std::size_t(i)];
        if (!st.events.agents[std::size_t(i)].acted) continue;
        const double move = a.config->speed * c.dt, alpha = a.config->reward.alpha_r;
        const double term = st.events.agents[std::size_t(i)].reward.obstacle;
        ASSERT_GE(term, 1.0 - std::exp(alpha * move) - 1e-9) << "agent " << i << ", step " << st.step;
        ++scanned;
        // How far the old map's d_O would have moved: more than the step's length when the scan revealed a cell.
        revealed += a.view.percept.obstacle.distance < seen_before[std::size_t(i)] - move - 1e-9;
      }
    }
  }
  EXPECT_GT(scanned, 500);
  EXPECT_GT(revealed, 5);  // scans did reveal nearer cells, which the term left out
}

TEST(Scans, APersistentMapKeepsWhatEarlierEpisodesSawUntilForgotten) {
  const auto arena = map_arena("maps/forest.yaml");
  GameConfig c = own_map_config();
  c.pursuer.map.persist = true;  // the evader's map lives for an episode
  const Sim sim(arena, c);
  SimState st(sim);
  const world::Scenario& s = arena->map().scenarios.front();
  const std::array<Steering, 2> none{};
  reset(sim, st, s, 1);
  for (int k = 0; k < 50 && !st.done; ++k) step(sim, st, none);
  const long long pursuer_known = st.map(0)->known_cells(), evader_known = st.map(1)->known_cells();
  reset(sim, st, s, 2);
  EXPECT_GE(st.map(0)->known_cells(), pursuer_known);   // kept, and the new reset's scan added to it
  EXPECT_LT(st.map(1)->known_cells(), evader_known);    // cleared, then one scan
  st.forget_maps();
  EXPECT_EQ(st.map(0)->known_cells(), 0);
}

// The cells of a map that are occupied now, by their keys.
std::set<sense::CellKey> occupied_now(const sense::ScanMap& map) {
  std::set<sense::CellKey> out;
  map.for_each_known([&](const sense::CellKey& key, float log_odds) {
    if (log_odds > 0.0f) out.insert(key);
  });
  return out;
}

TEST(Scans, ATraceRecordsEveryFramesReadingsAndTheMapsGrowth) {
  // The pursuer scans every 3 steps and keeps its map over episodes; the evader scans every step.
  const auto arena = map_arena("maps/forest.yaml");
  GameConfig c = own_map_config();
  c.pursuer.sensors.lidar.period = 3;
  c.pursuer.map.persist = true;
  const Sim sim(arena, c);
  SimState st(sim);
  Rng rng(8);
  std::vector<Steering> u(2);
  int flips_off_frame0 = 0, frees = 0;
  for (const std::uint64_t seed : {5u, 6u}) {  // the second episode starts from the pursuer's kept map
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    Trace trace;
    trace.reserve(sim.max_steps(), 2);
    reset(sim, st, arena->map().scenarios[seed % 2], seed);
    trace.record(st, false);
    std::array<std::set<sense::CellKey>, 2> replayed;  // the flips applied in order
    std::size_t applied = 0;
    for (int k = 0;; ++k) {
      ASSERT_EQ(trace.frame_count(), k + 1);
      ASSERT_EQ(trace.values(), 128);
      for (int i = 0; i < 2; ++i) {
        const int first = trace.value_first[std::size_t(trace.slot_first[std::size_t(i)])];
        for (int r = 0; r < 64; ++r) {
          ASSERT_EQ(trace.readings[std::size_t(k * 128 + first + r)], float(lidar_ranges(st, i)[std::size_t(r)]));
          ASSERT_EQ(trace.echoes[std::size_t(k * 128 + first + r)], lidar_echoes(st, i)[std::size_t(r)]);
        }
        const int scanned = trace.scan_frames[std::size_t(k * 2 + i)];
        ASSERT_EQ(scanned, i == 0 ? k - k % 3 : k) << "frame " << k;
      }
      for (; applied < trace.map_flips.size(); ++applied) {
        const MapFlip& m = trace.map_flips[applied];
        ASSERT_EQ(m.frame, k);
        const sense::CellKey key = st.map(m.agent)->key_of(m.centre);
        ASSERT_EQ(st.map(m.agent)->centre(key), m.centre);
        if (m.occupied) {
          ASSERT_TRUE(replayed[std::size_t(m.agent)].insert(key).second) << "a cell occupied twice";
        } else {
          ASSERT_EQ(replayed[std::size_t(m.agent)].erase(key), 1u) << "a free cell freed";
          ++frees;
        }
        flips_off_frame0 += k > 0;
      }
      for (int i = 0; i < 2; ++i) ASSERT_EQ(replayed[std::size_t(i)], occupied_now(*st.map(i))) << "frame " << k;
      if (st.done || k == 120) break;
      for (Steering& cmd : u) cmd = {uniform(rng, -0.3, 0.3), uniform(rng, -0.2, 0.2)};
      step(sim, st, u);
      trace.record(st, true);
    }
  }
  EXPECT_GT(flips_off_frame0, 50);  // the maps grew during the episodes, not only at their starts
  EXPECT_GT(frees, 0);              // and cells seen occupied were later seen free
}

TEST(Scans, AnAgentOfItsOwnMapAvoidsOnlyWhatItHasSeen) {
  // A ball between the pursuer and a motionless evader: pure pursuit flies straight at it. The guard, fed by the
  // world, or by a map from a lidar that looks ahead, turns away; fed by a map from a lidar that looks back, it
  // never learns of the ball, and the pursuer runs into it (collisions stay with the world).
  world::Scenario s = testing::scenario("s", Vec3(4, 10, 10), Vec3(26, 10, 10));
  const auto arena = testing::make_arena(Vec3(30, 20, 20), {{Vec3(15, 10, 10), 1.5}}, {s});
  const auto collisions = [&](bool own_map, double mount_azimuth) {
    GameConfig c = preset("peg3d");
    c.collision = CollisionMode::kPenalize;
    c.time_limit = 20.0;
    c.pursuer.policy = "pure-pursuit";
    c.evader.policy = "flee";
    c.evader.speed = 0.0;
    if (own_map) {
      c.pursuer.sensors.lidar = lidar(12, 3, 30.0, 8.0);
      c.pursuer.sensors.lidar.azimuth_fov = 90.0;
      c.pursuer.sensors.lidar.mount_azimuth = mount_azimuth;
      c.pursuer.map.enabled = true;
      c.pursuer.observation.obstacles = ObstacleSource::kOwnMap;
    }
    const Sim sim(arena, c);
    return testing::play_once(sim, s, 1).collisions;
  };
  EXPECT_EQ(collisions(false, 0.0), 0);
  EXPECT_EQ(collisions(true, 0.0), 0);
  EXPECT_GT(collisions(true, 180.0), 0);
}

const sense::DepthCamera* camera_of(const Sim& sim, Role role, int rank) {
  return dynamic_cast<const sense::DepthCamera*>(sim.sensor(role, rank, "camera"));
}

// Agent i's camera image equals what its pixels' rays meet by the reference, as depths along the optical axis;
// returns how many pixels returned an echo and how many met a mover.
std::pair<int, int> expect_image_matches(const Sim& sim, const SimState& st, int i) {
  const AgentState& a = st.agents[std::size_t(i)];
  const sense::DepthCamera& camera = *camera_of(sim, a.role, a.rank);
  std::vector<Ray> rays(std::size_t(camera.pixels()));
  camera.rays_at(a.kinematics.position, a.kinematics.heading, rays);
  const auto want = reference_hits(sim, st, i, rays, camera.config().range, camera.config().sees_agents);
  const sense::Reading& got = *st.reading(i, "camera");
  EXPECT_EQ(got.values.size(), want.size());
  int echoes = 0, on_movers = 0;
  for (std::size_t k = 0; k < want.size(); ++k) {
    const bool met = want[k].target != sense::RayTarget::kNone;
    EXPECT_EQ(got.echo[k], met ? 1 : 0) << "step " << st.step << " agent " << i << " pixel " << k;
    const double depth = met ? want[k].distance * rays[k].direction.dot(camera.pinhole_at(a.kinematics.heading).forward)
                             : camera.config().range;
    EXPECT_NEAR(got.values[k], depth, 1e-9) << "step " << st.step << " agent " << i << " pixel " << k;
    echoes += met, on_movers += want[k].target == sense::RayTarget::kMover;
  }
  return {echoes, on_movers};
}

sense::DepthCameraConfig camera(int width, int height, double range) {
  sense::DepthCameraConfig c;
  c.width = width, c.height = height, c.range = range;
  return c;
}

// Random steering for whole games of agents with cameras (the evader's every other step, looking up a little),
// checking every image against the reference.
void check_camera_game(const char* map, MoverDynamics dynamics, int steps, int min_on_movers, std::size_t scenarios) {
  const auto arena = map_arena(map);
  GameConfig c = preset("peg3d");
  c.mover_dynamics = dynamics;
  c.collision = CollisionMode::kPenalize;
  c.pursuer.sensors.camera = camera(16, 12, 15.0);
  c.evader.sensors.camera = camera(10, 6, 8.0);
  c.evader.sensors.camera.period = 2;
  c.evader.sensors.camera.hfov = 120.0;
  c.evader.sensors.camera.mount_elevation = 20.0;
  const Sim sim(arena, c);
  SimState st(sim);
  Rng rng(8);
  int images = 0, echoes = 0, on_movers = 0;
  const auto check = [&](int i) {
    const auto [e, m] = expect_image_matches(sim, st, i);
    ++images, echoes += e, on_movers += m;
  };
  const auto& all = arena->map().scenarios;
  for (std::size_t k = 0; k < std::min(scenarios, all.size()); ++k) {
    reset(sim, st, all[k], 2);
    for (int i = 0; i < st.agent_count(); ++i) check(i);
    std::vector<Steering> u(std::size_t(st.agent_count()));
    for (int n = 0; n < steps && !st.done; ++n) {
      for (Steering& s_ : u) s_ = {uniform(rng, -0.3, 0.3), uniform(rng, -0.2, 0.2)};
      const StepEvents& ev = step(sim, st, u);
      for (int i = 0; i < st.agent_count(); ++i) {
        const int period = st.agents[std::size_t(i)].role == Role::kPursuer ? 1 : 2;
        const bool due = ev.agents[std::size_t(i)].acted && st.step % period == 0;
        EXPECT_EQ(st.reading(i, "camera")->step == st.step, due) << "step " << st.step << " agent " << i;
        if (due) check(i);
        if (::testing::Test::HasFailure()) return;
      }
    }
  }
  std::printf("%s: %d images checked, %d echoes, %d on movers\n", map, images, echoes, on_movers);
  EXPECT_GT(images, 25);
  EXPECT_GT(echoes, 1000);
  EXPECT_GE(on_movers, min_on_movers);
}

TEST(Scans, CameraImagesEqualTestingEverySolidAndAgentOnForest) {
  check_camera_game("maps/forest.yaml", MoverDynamics::kShared, 120, 0, 99);
}

TEST(Scans, CameraImagesEqualTestingEveryMoverAtTheInstantOfTheImageOnQuarry) {
  check_camera_game("maps/quarry.yaml", MoverDynamics::kShared, 25, 50, peg3d::testing::release_or_sanitized(3, 1));
}

TEST(Scans, CameraImagesSeeTheBodiesWhereThePushModeRunMovedThem) {
  check_camera_game("maps/quarry.yaml", MoverDynamics::kPush, 20, 20, 1);
}

TEST(Scans, ACameraFeedsItsHoldersMapAndItsObservation) {
  // The pursuer senses obstacles only through a map its camera builds; its observation holds its latest image.
  const auto arena = map_arena("maps/forest.yaml");
  GameConfig c = preset("peg3d");
  c.pursuer.sensors.camera = camera(24, 16, 10.0);
  c.pursuer.sensors.camera.noise = 0.02;
  c.pursuer.map.enabled = true;
  c.pursuer.observation.obstacles = ObstacleSource::kOwnMap;
  const Sim sim(arena, c);
  SimState st(sim);
  reset(sim, st, arena->map().scenarios.front(), 3);
  const sense::DepthCamera& cam = *camera_of(sim, Role::kPursuer, 0);
  const ObservationTable table = observation_table(sim, Role::kPursuer, 0, 0);
  const sense::Segment* image = table.find("camera.depth");
  ASSERT_NE(image, nullptr);
  EXPECT_EQ(image->shape, (std::vector<int>{16, 24}));
  EXPECT_EQ(observation_table(sim, Role::kEvader, 0, 0).find("camera.depth"), nullptr);  // the evader has none
  // A map of the pursuer's own, fed each image's points from its readings: each echo's depth back along its
  // pixel's ray, beyond the range where there is none.
  sense::ScanMap mine(c.pursuer.map, arena->bounds().lo, arena->bounds().hi);
  std::vector<Ray> rays(std::size_t(cam.pixels()));
  std::vector<Vec3> points(rays.size());
  std::vector<float> observed(std::size_t(table.size()));
  Rng rng(4);
  std::vector<Steering> u(2);
  int found = 0;
  for (int k = 0; k < 150 && !st.done; ++k) {
    const AgentState& a = st.agents[0];
    const sense::Reading& r = *st.reading(0, "camera");
    cam.rays_at(a.kinematics.position, a.kinematics.heading, rays);
    for (std::size_t p = 0; p < rays.size(); ++p) {
      const double t = r.echo[p] != 0 ? r.values[p] / cam.axis_cosine(int(p)) : 10.0 + 0.5;
      points[p] = a.kinematics.position + t * rays[p].direction;
    }
    mine.insert(a.kinematics.position, points, 10.0);
    ASSERT_EQ(st.map(0)->known_cells(), mine.known_cells()) << "step " << st.step;
    ASSERT_EQ(st.map(0)->occupied_cells(), mine.occupied_cells()) << "step " << st.step;
    found += observe(st, 0).field.found;
    write_observation(sim, st, 0, table, observed);
    for (int p = 0; p < image->size; ++p) {
      ASSERT_EQ(observed[std::size_t(image->offset + p)], float(r.values[std::size_t(p)])) << "step " << st.step;
    }
    for (Steering& s_ : u) s_ = {uniform(rng, -0.3, 0.3), uniform(rng, -0.2, 0.2)};
    step(sim, st, u);
  }
  EXPECT_GT(found, 20);  // the map held trunks the pursuer sensed
  EXPECT_GT(mine.occupied_cells(), 50);
}

// `hash(seed)` run on 2 and 4 threads at once, each equal to `here`, the one-thread value.
template <class Hash>
void expect_same_on_threads(const Hash& hash, std::uint64_t here) {
  for (const int threads : {2, 4}) {
    std::vector<std::uint64_t> got(static_cast<std::size_t>(threads));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back([&, t] { got[std::size_t(t)] = hash(); });
    for (std::thread& t : pool) t.join();
    for (std::uint64_t g : got) EXPECT_EQ(g, here) << threads << " threads";
  }
}

// A game of FACL agents sensing through their own maps on forest, hashed: positions of every agent every step.
std::uint64_t own_map_game_hash(const Sim& sim, std::uint64_t seed) {
  Fnv1a h;
  for (const world::Scenario& s : sim.arena().map().scenarios) {
    Trace t;
    testing::play_once(sim, s, seed, &t);
    for (int f = 0; f < t.frame_count(); ++f) {
      for (int i = 0; i < s.agents(); ++i) {
        h.add_value(t.at(f, i).state.position);
        h.add_value(t.at(f, i).reward);  // the repulsion term measured in the agent's own map
      }
    }
  }
  return h.value();
}

TEST(Scans, AnOwnMapGameIsTheSameOnAnyThreadCount) {
  GameConfig c = own_map_config();
  c.pursuer.sensors.lidar.noise = c.evader.sensors.lidar.noise = 0.02;
  c.time_limit = 30.0;
  const Sim sim(map_arena("maps/forest.yaml"), c);
  const std::uint64_t here = own_map_game_hash(sim, 5);
  expect_same_on_threads([&] { return own_map_game_hash(sim, 5); }, here);
  // Sensing through the map moves the agents: the game differs from the one that senses the world.
  GameConfig world = c;
  world.pursuer.observation.obstacles = world.evader.observation.obstacles = ObstacleSource::kWorld;
  EXPECT_NE(own_map_game_hash(Sim(map_arena("maps/forest.yaml"), world), 5), here);
  EXPECT_EQ(here, 0x80943ab0d929fd55ull) << std::hex << here;
}

// A sensing game's readings, hashed step by step: quarry's movers, agents seen, noise and dropouts.
std::uint64_t sensing_game_hash(const Sim& sim, std::uint64_t seed) {
  SimState st(sim);
  Fnv1a h;
  Rng rng(seed);
  for (const world::Scenario& s : sim.arena().map().scenarios) {
    reset(sim, st, s, seed);
    std::vector<Steering> u(std::size_t(st.agent_count()));
    while (!st.done && st.step < 150) {
      h.add_span(st.sensing.values);
      h.add_span(st.sensing.echo);
      for (Steering& s_ : u) s_ = {uniform(rng, -0.3, 0.3), uniform(rng, -0.2, 0.2)};
      step(sim, st, u);
    }
  }
  return h.value();
}

TEST(Scans, ASensingGameIsTheSameOnAnyThreadCount) {
  GameConfig c = preset("peg3d");
  c.collision = CollisionMode::kPenalize;
  c.pursuer.sensors.lidar = lidar(16, 4, 60.0, 12.0);
  c.pursuer.sensors.lidar.noise = 0.03;
  c.pursuer.sensors.lidar.dropout = 0.1;
  c.evader.sensors.lidar = c.pursuer.sensors.lidar;
  c.evader.sensors.lidar.period = 2;
  const Sim sim(map_arena("maps/quarry.yaml"), c);
  const std::uint64_t here = sensing_game_hash(sim, 5);
  expect_same_on_threads([&] { return sensing_game_hash(sim, 5); }, here);
  EXPECT_NE(sensing_game_hash(sim, 6), here);  // the seed reaches the readings
  // The golden value: readings that move must be explained in the commit that updates it.
  EXPECT_EQ(here, 0xd57ba1315a801568ull) << std::hex << here;
}

TEST(Scans, ACameraGameIsTheSameOnAnyThreadCount) {
  GameConfig c = preset("peg3d");
  c.collision = CollisionMode::kPenalize;
  c.pursuer.sensors.camera = camera(16, 12, 12.0);
  c.pursuer.sensors.camera.noise = 0.03;
  c.pursuer.sensors.camera.dropout = 0.1;
  c.evader.sensors.camera = c.pursuer.sensors.camera;
  c.evader.sensors.camera.period = 2;
  const Sim sim(map_arena("maps/quarry.yaml"), c);
  const std::uint64_t here = sensing_game_hash(sim, 5);
  expect_same_on_threads([&] { return sensing_game_hash(sim, 5); }, here);
  EXPECT_NE(sensing_game_hash(sim, 6), here);
  // The golden value: readings that move must be explained in the commit that updates it.
  EXPECT_EQ(here, 0x21ce0af910629534ull) << std::hex << here;
}

}  // namespace
}  // namespace peg3d::game
