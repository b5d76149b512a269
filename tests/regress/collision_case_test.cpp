// Collision cases: how a case file and its motion files read, what a mistake in them says, and one case played
// against its analytic time of impact.
#include "regress/collision_case.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "geometry/angles.hpp"

namespace peg3d::regress {
namespace {

namespace fs = std::filesystem;

class CollisionCaseFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("peg3d-case-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "my-case");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const fs::path& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }
  /// The InputError that loading (and, when it loads, running) the case raises.
  InputError error_of(const fs::path& path) {
    try {
      run_case(load_case(path), false);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no error for " << path;
    return InputError("none");
  }
  fs::path dir_;
  const fs::path shapes_ = fs::path(PEG3D_SOURCE_DIR) / "tests/collision/maps/shapes.yaml";
};

TEST_F(CollisionCaseFiles, AFolderOrAFileAndPathsRelativeToIt) {
  write("my-case/case.yaml", "map: ../maps/m.yaml\nscenario: S2\nconfig: cfg.json\nset: [time_limit=5]\nseed: 9\n"
                             "agents:\n  pursuer: {commands: p.commands}\n  evader1: {scripted: flee}\n");
  write("my-case/p.commands", "# t da dt\n0 0 0\n\n2.5 1 -2  # a turn\n");
  const CollisionCase c = load_case(dir_ / "my-case");
  EXPECT_EQ(c.name, "my-case");
  EXPECT_EQ(c.golden, dir_ / "my-case" / "golden.log");
  EXPECT_EQ(c.map, (dir_ / "maps/m.yaml").lexically_normal());
  EXPECT_EQ(c.config, (dir_ / "my-case/cfg.json").lexically_normal().string());
  EXPECT_EQ(c.scenario, "S2");
  EXPECT_EQ(c.seed, 9u);
  ASSERT_EQ(c.drivers.size(), 2u);
  ASSERT_EQ(c.drivers[0].commands.size(), 2u);
  EXPECT_EQ(c.drivers[0].commands[1].time, 2.5);
  EXPECT_DOUBLE_EQ(c.drivers[0].commands[1].command.d_alpha, kPi / 180.0);
  EXPECT_DOUBLE_EQ(c.drivers[0].commands[1].command.d_theta, -2.0 * kPi / 180.0);
  EXPECT_EQ(c.drivers[1].kind, AgentDriver::Kind::kScripted);

  write("single.yaml", "map: maps/m.yaml\nagents:\n  evader: {waypoints: [[1, 2, 3], [4, 5, 6, 7.5]]}\n");
  const CollisionCase s = load_case(dir_ / "single.yaml");
  EXPECT_EQ(s.name, "single");
  EXPECT_EQ(s.golden, dir_ / "single.log");
  EXPECT_EQ(s.config, "peg3d");
  ASSERT_EQ(s.drivers[0].waypoints.size(), 2u);
  EXPECT_EQ(s.drivers[0].waypoints[0].time, -1.0);
  EXPECT_EQ(s.drivers[0].waypoints[1].time, 7.5);
  EXPECT_EQ(find_cases(dir_), (std::vector<fs::path>{dir_ / "my-case", dir_ / "single.yaml"}));
}

TEST_F(CollisionCaseFiles, MistakesNameTheFileTheLineAndTheField) {
  const auto expect = [&](const fs::path& file, const InputError& e, int line, const std::string& field) {
    EXPECT_EQ(e.file(), file) << e.what();
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
  };
  const std::string map = "map: " + shapes_.string() + "\n";
  fs::path f = write("a.yaml", map + "colour: blue\n");
  expect(f, error_of(f), 2, "colour");
  f = write("b.yaml", map + "agents:\n  pursuer: {scripted: facl}\n");
  expect(f, error_of(f), 3, "agents.pursuer.scripted");
  f = write("c.yaml", map + "agents:\n  pursuer: {commands: [[0, 0, 0], [1, x, 0]]}\n");
  expect(f, error_of(f), 3, "agents.pursuer.commands[1][1]");
  const fs::path motion = write("bad.commands", "0 0 0\n1 0\n");
  f = write("d.yaml", map + "agents:\n  pursuer: {commands: bad.commands}\n");
  expect(motion, error_of(f), 2, "");
  write("late.commands", "2 0 0\n1 0 0\n");
  f = write("e.yaml", map + "agents:\n  pursuer: {commands: late.commands}\n");
  expect(dir_ / "late.commands", error_of(f), 2, "");
  f = write("f.yaml", map + "agents:\n  pursuer_7: {commands: [[0, 0, 0]]}\n");
  expect(f, error_of(f), 3, "agents.pursuer_7");
  f = write("g.yaml", map + "scenario: nowhere\n");
  expect(f, error_of(f), 2, "scenario");
  f = write("h.yaml", map + "agents:\n  pursuer: {scripted: flee}\n");
  expect(f, error_of(f), 3, "agents.pursuer.scripted");  // flee is an evader's strategy
  EXPECT_EQ(error_of(dir_ / "none").file(), dir_ / "none");
}

TEST_F(CollisionCaseFiles, AStraightRunHitsTheSphereAtTheAnalyticTime) {
  // From x = 5 towards sphere 0 of shapes.yaml (centre x = 15, radius 1): the 0.25 m agent touches it after
  // 8.75 m at 1.1 m/s, at 7.954545 s, at the point (14, 10, 10) with the normal -x.
  const fs::path f = write("run.yaml", "map: " + shapes_.string() + "\nscenario: toward-sphere\n"
                                       "set: [pursuer.guard.enabled=false, pursuer.motion_space=false, evader.speed=0]\n"
                                       "agents:\n  pursuer_0: {commands: [[0, 0, 0]]}\n");
  const CollisionLog log = run_case(load_case(f), false);
  EXPECT_EQ(log.outcome, "pursuer-collision");
  ASSERT_EQ(log.events.size(), 1u);
  EXPECT_EQ(log.events[0].agent, "pursuer_0");
  EXPECT_EQ(log.events[0].hit, "sphere:0");
  EXPECT_NEAR(log.events[0].time, 8.75 / 1.1, 1e-6);
  EXPECT_NEAR((log.events[0].point - Vec3(14, 10, 10)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((log.events[0].normal - Vec3(-1, 0, 0)).norm(), 0.0, 1e-6);
  EXPECT_EQ(log.agents.size(), 2u);
  // The same case, played again, logs the same trajectory bit for bit.
  EXPECT_EQ(run_case(load_case(f), false).trajectory_hash, log.trajectory_hash);
}

TEST_F(CollisionCaseFiles, CasesWrittenBeforeIssue37StillNameTheirAgents) {
  // Then the only agent of a role was "pursuer" and agents of teams "pursuer1"; each still drives the agent now
  // named pursuer_0 or pursuer_1 (the same final states as the current label, not those of no driver), while
  // "pursuer" alone stays refused in a team, where it named no agent.
  const std::string head = "map: " + shapes_.string() +
                           "\nset: [pursuer.guard.enabled=false, pursuer.motion_space=false, evader.speed=0, time_limit=3]\n";
  const auto finals = [&](const std::string& scenario, const std::string& label) {
    const std::string agents = label.empty() ? "" : "agents:\n  " + label + ": {commands: [[0, 20, 10]]}\n";
    const fs::path f = write(scenario + "-" + (label.empty() ? "none" : label) + ".yaml",
                             head + "scenario: " + scenario + "\n" + agents);
    std::vector<Vec3> out;
    for (const auto& a : run_case(load_case(f), false).agents) out.push_back(a.position);
    return out;
  };
  EXPECT_EQ(finals("toward-sphere", "pursuer"), finals("toward-sphere", "pursuer_0"));
  EXPECT_NE(finals("toward-sphere", "pursuer"), finals("toward-sphere", ""));
  EXPECT_EQ(finals("pack", "pursuer1"), finals("pack", "pursuer_1"));
  EXPECT_NE(finals("pack", "pursuer1"), finals("pack", ""));
  EXPECT_NE(finals("pack", "pursuer1"), finals("pack", "pursuer_0"));
  const fs::path team = write("team.yaml", head + "scenario: pack\nagents:\n  pursuer: {commands: [[0, 0, 0]]}\n");
  EXPECT_EQ(error_of(team).field(), "agents.pursuer");
}

}  // namespace
}  // namespace peg3d::regress
