// The collision log: it reads back what it writes, its comparison reports a millimetre and forgives the
// printing's rounding, and a malformed log is an input error naming its line.
#include "regress/collision_log.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace peg3d::regress {
namespace {

CollisionLog sample() {
  CollisionLog log;
  log.name = "grazing-pass";
  log.outcome = "pursuer-collision";
  log.steps = 80;
  log.time = 8.0;
  log.events.push_back({80, 7.954545, "pursuer_0", "sphere:12", -1, {14, 10, 10}, {-1, 0, 0}, 0.0});
  log.events.push_back({80, 7.96, "evader_0", "mesh:0", 838, {1.5, 2.5, 0.25}, {0, 0.6, 0.8}, 0.001});
  log.captures.push_back({40, 4.0, "pursuer_0", "evader_1", 0.98});
  log.agents.push_back({"pursuer_0", {14.25, 10, 10}, 0.0, 1.570796, 8.75, true});
  log.agents.push_back({"evader_0", {33, 33, 18}, -3.14159, 1.570796, 0.0, false});
  log.movers.push_back({0, "box", {3, 4, 5}, Quat(0.5, 0.5, 0.5, 0.5)});
  log.trajectory_hash = 0x0123456789abcdefULL;
  return log;
}

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l == text; });
}

TEST(CollisionLog, ReadsTheLabelsOfFormatOneAsTheCurrentOnes) {
  // Before issue 37 the only agent of a role was "pursuer" and agents of teams "pursuer1": a golden log of then
  // reads as the same log with today's labels, so that it still compares equal to a new run.
  CollisionLog now = sample();  // a team: pursuer_0, pursuer_1 and one evader, with every kind of record
  now.events.push_back({81, 8.0, "pursuer_1", "agent:pursuer_0", -1, {1, 1, 1}, {0, 0, 1}, 0.0});
  now.captures[0] = {40, 4.0, "pursuer_1", "evader_0", 0.98};
  now.pushes.push_back({30, 3.0, "pursuer_0", 2, {1, 2, 3}, {0, 0, 1}});
  now.agents.insert(now.agents.begin() + 1, {"pursuer_1", {4.25, 10, 10}, 0.0, 1.570796, 8.75, true});
  std::string old = format_log(now);
  for (const auto& [label, then] : {std::pair<std::string, std::string>{"pursuer_0", "pursuer0"}, {"pursuer_1", "pursuer1"},
                                    {"evader_0", "evader"}}) {
    for (std::size_t at = old.find(label); at != std::string::npos; at = old.find(label, at)) old.replace(at, label.size(), then);
  }
  old.replace(old.find("format 2"), 8, "format 1");
  ASSERT_EQ(old.find("_0"), std::string::npos) << old;
  ASSERT_EQ(old.find("_1"), std::string::npos) << old;
  const CollisionLog back = parse_log(old, "old.log");
  EXPECT_EQ(format_log(back), format_log(now));
  EXPECT_TRUE(compare_logs(now, back, {}, /*strict=*/true).empty());
}

TEST(CollisionLog, ReadsBackWhatItWrites) {
  const CollisionLog log = sample();
  const std::string text = format_log(log);
  const CollisionLog back = parse_log(text, "golden.log");
  EXPECT_EQ(format_log(back), text);
  EXPECT_TRUE(compare_logs(log, back, {}, /*strict=*/true).empty());
  EXPECT_EQ(back.events[1].triangle, 838);
  EXPECT_EQ(back.events[0].triangle, -1);
  EXPECT_FALSE(back.agents[1].active);
  EXPECT_EQ(back.trajectory_hash, 0x0123456789abcdefULL);
}

TEST(CollisionLog, OneRecordPerLineThatReadsInADiff) {
  const std::string text = format_log(sample());
  EXPECT_NE(text.find("\nevent 1 step=80 time=7.954545 agent=pursuer_0 hit=sphere:12 triangle=- point=14.000000,10.000000,"
                      "10.000000 normal=-1.000000,0.000000,0.000000 penetration=0.000000\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\ncapture 1 step=40 time=4.000000 pursuer=pursuer_0 evader=evader_1 distance=0.980000\n"),
            std::string::npos);
  EXPECT_NE(text.find("\ntrajectory 0x0123456789abcdef\n"), std::string::npos);
}

TEST(CollisionLog, AMillimetreIsReportedTheRoundingOfTheLogIsNot) {
  const CollisionLog e = sample();
  CollisionLog a = e;
  a.events[0].point.x() += 0.5e-6;  // below the log's last printed digit
  a.events[0].time += 0.5e-6;
  EXPECT_TRUE(compare_logs(e, a, {}, false).empty());
  a = e;
  a.events[0].point.x() -= 1e-3;  // the obstacle a millimetre nearer
  a.events[0].time -= 1e-3 / 1.1;
  const auto d = compare_logs(e, a, {}, false);
  ASSERT_EQ(d.size(), 2u) << d.front();
  EXPECT_EQ(d[0], "event 1: time 7.954545 s -> 7.953636 s");
  EXPECT_EQ(d[1], "event 1: point (14.000000, 10.000000, 10.000000) -> (13.999000, 10.000000, 10.000000)");
}

TEST(CollisionLog, AVanishedOrNewEventIsNamed) {
  const CollisionLog e = sample();
  CollisionLog a = e;
  a.events.pop_back();
  EXPECT_TRUE(mentions(compare_logs(e, a, {}, false), "event 2: evader_0 hit mesh:0 at 7.960000 s -> (none)"));
  EXPECT_TRUE(mentions(compare_logs(a, e, {}, false), "event 2: (none) -> evader_0 hit mesh:0 at 7.960000 s"));
  a = e;
  a.events[0].hit = "sphere:11";
  a.events[1].triangle = 839;
  const auto d = compare_logs(e, a, {}, false);
  EXPECT_TRUE(mentions(d, "event 1: hit sphere:12 -> sphere:11"));
  EXPECT_TRUE(mentions(d, "event 2: triangle 838 -> 839"));
}

TEST(CollisionLog, CapturesAgentsAndMoversAreCompared) {
  const CollisionLog e = sample();
  CollisionLog a = e;
  a.captures.clear();
  a.agents[1].active = true;
  a.movers[0].position.z() += 0.01;
  const auto d = compare_logs(e, a, {}, false);
  EXPECT_TRUE(mentions(d, "capture 1: pursuer_0 caught evader_1 at 4.000000 s -> (none)"));
  EXPECT_TRUE(mentions(d, "agent evader_0: in the game no -> yes"));
  EXPECT_TRUE(mentions(d, "mover 0: final position (3.000000, 4.000000, 5.000000) -> (3.000000, 4.000000, 5.010000)"));
  // A quaternion and its negative are the same orientation.
  a = e;
  a.movers[0].orientation.coeffs() *= -1.0;
  EXPECT_TRUE(compare_logs(e, a, {}, false).empty());
}

TEST(CollisionLog, ADifferentHashIsANoteUnlessStrict) {
  const CollisionLog e = sample();
  CollisionLog a = e;
  a.trajectory_hash ^= 1;
  std::vector<std::string> notes;
  EXPECT_TRUE(compare_logs(e, a, {}, false, &notes).empty());
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("trajectory hash 0x0123456789abcdef -> 0x0123456789abcdee"), std::string::npos);
  EXPECT_EQ(compare_logs(e, a, {}, true).size(), 1u);
}

TEST(CollisionLog, AMalformedLogNamesItsLineAndField) {
  std::string text = format_log(sample());
  const auto fails_at = [](const std::string& t, int line, const std::string& field) {
    try {
      parse_log(t, "cases/x/golden.log");
      ADD_FAILURE() << "accepted: " << t;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "cases/x/golden.log");
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_EQ(e.field(), field) << e.what();
    }
  };
  std::string bad = text;
  bad.replace(bad.find("time=7.954545"), 13, "time=soon");
  fails_at(bad, 4, "event.time");
  bad = text;
  bad.replace(bad.find("point=14.000000,10.000000,"), 26, "point=14.000000,");
  fails_at(bad, 4, "event.point");
  bad = text;
  bad.replace(bad.find("active=no"), 9, "active=maybe");
  fails_at(bad, 8, "agent.active");
  fails_at(text + "collision 3\n", 11, "");
  fails_at(text.substr(0, text.find("trajectory")), 0, "");  // cut short: no hash
}

}  // namespace
}  // namespace peg3d::regress
