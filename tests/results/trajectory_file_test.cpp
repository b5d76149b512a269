// Trajectory files read back into the trace that wrote them: every number exactly (the CSV prints the
// shortest exact form), the nearest obstacle's point rebuilt from distance and angles, collisions and
// captures from the _hit and _active columns; a malformed file is an input error naming line and column.
#include "results/trajectory_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "support/scratch_dir.hpp"
#include "test_arena.hpp"

namespace peg3d::results {
namespace {

using peg3d::testing::ScratchDir;

// Two pursuers close in on a fleeing evader past a sphere: captures, obstacle percepts, a team's labels.
game::Trace team_chase() {
  const world::Scenario s = peg3d::testing::team("T", {{5, 5, 10}, {5, 12, 10}}, {{12, 5, 10}});
  const auto arena = peg3d::testing::make_arena(Vec3(35, 35, 20), {{Vec3(12, 8, 10), 1.5}}, {s});
  game::GameConfig c = game::preset("peg3d");
  c.pursuer.policy = "pure-pursuit";
  c.evader.policy = "flee";
  c.pursuer.speed = 2.0;
  c.evader.speed = 0.5;
  const game::Sim sim(arena, c);
  game::Trace trace;
  peg3d::testing::play_once(sim, s, 1, &trace);
  return trace;
}

void write(const std::filesystem::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

TEST(ResultsTrajectoryFile, ReadsBackEveryFrameExactly) {
  const ScratchDir dir;
  const game::Trace t = team_chase();
  ASSERT_EQ(t.captures.size(), 1u);
  write_trajectory_csv(dir / "t.csv", t);
  const game::Trace back = read_trajectory_csv(dir / "t.csv");
  ASSERT_EQ(back.agents, 3);
  EXPECT_EQ(back.roles, t.roles);
  EXPECT_EQ(back.times, t.times);
  bool some_obstacle = false;
  for (int k = 0; k < t.frame_count(); ++k) {
    for (int i = 0; i < 3; ++i) {
      const game::AgentFrame &a = t.at(k, i), &b = back.at(k, i);
      ASSERT_EQ(b.state.position, a.state.position);
      ASSERT_EQ(b.state.heading.alpha, a.state.heading.alpha);
      ASSERT_EQ(b.percept.target_distance, a.percept.target_distance);
      ASSERT_EQ(b.percept.to_obstacle.elevation, a.percept.to_obstacle.elevation);
      ASSERT_EQ(b.command.d_theta, a.command.d_theta);
      ASSERT_EQ(b.reward, a.reward);
      ASSERT_EQ(b.active, a.active);
      ASSERT_EQ(b.percept.obstacle.found, a.percept.obstacle.found) << k << " " << i;
      if (a.percept.obstacle.found) {
        some_obstacle = true;
        ASSERT_LT((b.percept.obstacle.point - a.percept.obstacle.point).norm(), 1e-9);
      }
    }
  }
  EXPECT_TRUE(some_obstacle);
  ASSERT_EQ(back.captures.size(), 1u);
  EXPECT_EQ(back.captures[0].step, t.captures[0].step);
  EXPECT_EQ(back.captures[0].evader, t.captures[0].evader);
  EXPECT_EQ(back.captures[0].pursuer, t.captures[0].pursuer);
}

TEST(ResultsTrajectoryFile, FilesWrittenBeforeIssue37ReadAsToday) {
  // Then the only agent of a role was "evader" and agents of teams "pursuer0", "pursuer1": columns evader_x,
  // pursuer1_hit, ... The same file with those labels reads into the same trace.
  const ScratchDir dir;
  const game::Trace t = team_chase();
  write_trajectory_csv(dir / "now.csv", t);
  std::ifstream in(dir / "now.csv");
  std::string header, rest, line;
  std::getline(in, header);
  while (std::getline(in, line)) rest += line + "\n";
  ASSERT_NE(header.find("pursuer_1_x"), std::string::npos) << header;
  for (const auto& [now, then] : {std::pair<std::string, std::string>{"pursuer_0_", "pursuer0_"}, {"pursuer_1_", "pursuer1_"},
                                  {"evader_0_", "evader_"}}) {
    for (std::size_t at = header.find(now); at != std::string::npos; at = header.find(now, at)) header.replace(at, now.size(), then);
  }
  write(dir / "then.csv", header + "\n" + rest);
  const game::Trace a = read_trajectory_csv(dir / "now.csv"), b = read_trajectory_csv(dir / "then.csv");
  EXPECT_EQ(b.roles, a.roles);
  EXPECT_EQ(b.times, a.times);
  ASSERT_EQ(b.frames.size(), a.frames.size());
  for (std::size_t f = 0; f < a.frames.size(); ++f) ASSERT_EQ(b.frames[f].state.position, a.frames[f].state.position) << f;
  ASSERT_EQ(b.captures.size(), a.captures.size());
  EXPECT_EQ(b.captures[0].pursuer, a.captures[0].pursuer);
}

TEST(ResultsTrajectoryFile, CollisionsReadBackWithTheirKindAndFrame) {
  const ScratchDir dir;
  game::Trace t = team_chase();
  game::CollisionEvent e;
  e.step = 3, e.time = t.times[3], e.agent = 1, e.kind = world::ObstacleKind::kMesh;
  t.collisions.push_back(e);
  write_trajectory_csv(dir / "t.csv", t);
  const game::Trace back = read_trajectory_csv(dir / "t.csv");
  ASSERT_EQ(back.collisions.size(), 1u);
  EXPECT_EQ(back.collisions[0].step, 3);
  EXPECT_EQ(back.collisions[0].agent, 1);
  EXPECT_EQ(back.collisions[0].kind, world::ObstacleKind::kMesh);
  EXPECT_EQ(back.collisions[0].point, t.at(3, 1).state.position);
}

TEST(ResultsTrajectoryFile, FilesWithoutActivityColumnsReadAsEveryoneActive) {
  const ScratchDir dir;
  std::string header = "t,pursuer_x,pursuer_y,pursuer_z,evader_x,evader_y,evader_z,pursuer_alpha,pursuer_theta,"
                       "evader_alpha,evader_theta,distance";
  std::string row = "0,1,2,3,4,5,6,0,1.5,0,1.5,3";
  for (const char* a : {"pursuer", "evader"}) {
    for (const char* c : {"d_target", "target_az", "target_el", "d_obstacle", "obstacle_az", "obstacle_el", "d_alpha",
                          "d_theta", "reward", "pinned"}) {
      header += std::string(",") + a + "_" + c;
      row += ",0";
    }
  }
  write(dir / "old.csv", header + "\n" + row + "\n");
  const game::Trace t = read_trajectory_csv(dir / "old.csv");
  ASSERT_EQ(t.frame_count(), 1);
  EXPECT_TRUE(t.at(0, 0).active && t.at(0, 1).active);
  EXPECT_EQ(t.at(0, 1).state.position, Vec3(4, 5, 6));
}

std::string message_of(const std::filesystem::path& file) {
  try {
    read_trajectory_csv(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ResultsTrajectoryFile, MalformedFilesNameTheLineAndColumn) {
  const ScratchDir dir;
  const game::Trace t = team_chase();
  write_trajectory_csv(dir / "good.csv", t);
  std::ifstream in(dir / "good.csv");
  std::string header, row1, row2;
  std::getline(in, header), std::getline(in, row1), std::getline(in, row2);

  write(dir / "short.csv", header + "\n" + row1 + "\n1,2\n");
  EXPECT_NE(message_of(dir / "short.csv").find(":3"), std::string::npos) << message_of(dir / "short.csv");
  EXPECT_NE(message_of(dir / "short.csv").find("fields"), std::string::npos);

  std::string bad = row2;
  bad.replace(bad.find(',') + 1, 0, "x");  // pursuer_0_x becomes "x<number>"
  write(dir / "word.csv", header + "\n" + row1 + "\n" + bad + "\n");
  EXPECT_NE(message_of(dir / "word.csv").find("pursuer_0_x"), std::string::npos) << message_of(dir / "word.csv");

  write(dir / "back.csv", header + "\n" + row2 + "\n" + row1 + "\n");
  EXPECT_NE(message_of(dir / "back.csv").find("increase"), std::string::npos);

  std::string no_z = header;
  no_z.replace(no_z.find("evader_0_z"), 10, "evader_0_q");
  write(dir / "col.csv", no_z + "\n");
  EXPECT_NE(message_of(dir / "col.csv").find("evader_0_z"), std::string::npos) << message_of(dir / "col.csv");

  write(dir / "empty.csv", "");
  EXPECT_NE(message_of(dir / "empty.csv").find("header"), std::string::npos);
  write(dir / "other.csv", "a,b\n1,2\n");
  EXPECT_NE(message_of(dir / "other.csv").find("not a trajectory file"), std::string::npos);
}

}  // namespace
}  // namespace peg3d::results
