#include "sweep/progress_reporter.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "sweep/parallel_runner.hpp"

namespace peg3d::sweep {
namespace {

using namespace std::chrono_literals;

// A clock the test moves by hand: no sleeping, no dependence on the machine's speed.
struct FakeClock {
  std::chrono::steady_clock::time_point now{};
  std::function<std::chrono::steady_clock::time_point()> source() {
    return [this] { return now; };
  }
};

// A FILE* the test can read back.
class CapturedFile {
 public:
  CapturedFile() : file_(std::tmpfile(), &std::fclose) {}
  std::FILE* get() const { return file_.get(); }
  std::string text() const {
    std::fflush(file_.get());
    std::rewind(file_.get());
    std::string out;
    for (int c = std::fgetc(file_.get()); c != EOF; c = std::fgetc(file_.get())) out += static_cast<char>(c);
    return out;
  }

 private:
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
};

std::size_t count_of(const std::string& text, std::string_view part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

ProgressSnapshot quarter_done() {
  // 1250 of 5000 episodes after 14.65 s: 85.3 ep/s, 43.95 s left.
  return {.total_runs = 40, .runs_done = 10, .total_episodes = 5000, .episodes_done = 1250, .elapsed_s = 14.65};
}

TEST(SweepProgressReporter, FormatsDurations) {
  EXPECT_EQ(format_duration(0.0), "0s");
  EXPECT_EQ(format_duration(42.4), "42s");
  EXPECT_EQ(format_duration(59.6), "1m00s");
  EXPECT_EQ(format_duration(185.0), "3m05s");
  EXPECT_EQ(format_duration(2 * 3600.0 + 3 * 60.0 + 10.0), "2h03m");
  EXPECT_EQ(format_duration(3 * 86400.0 + 4 * 3600.0), "3d04h");
  EXPECT_EQ(format_duration(std::nan("")), "--");
  EXPECT_EQ(format_duration(-1.0), "--");
}

TEST(SweepProgressReporter, RatesAndEtaFollowFromSnapshot) {
  const ProgressSnapshot s = quarter_done();
  EXPECT_DOUBLE_EQ(progress_fraction(s), 0.25);
  EXPECT_DOUBLE_EQ(episodes_per_second(s), 1250.0 / 14.65);
  EXPECT_DOUBLE_EQ(eta_seconds(s), 14.65 * 3.0);
}

TEST(SweepProgressReporter, FractionFallsBackToRuns) {
  const ProgressSnapshot s{.total_runs = 8, .runs_done = 2, .total_episodes = 0, .episodes_done = 0, .elapsed_s = 1};
  EXPECT_DOUBLE_EQ(progress_fraction(s), 0.25);
  EXPECT_DOUBLE_EQ(progress_fraction(ProgressSnapshot{}), 1.0);  // nothing planned: nothing left
}

TEST(SweepProgressReporter, UnknownRateAndEtaBeforeProgress) {
  const ProgressSnapshot s{.total_runs = 4, .runs_done = 0, .total_episodes = 100, .episodes_done = 0, .elapsed_s = 0};
  EXPECT_TRUE(std::isnan(episodes_per_second(s)));
  EXPECT_TRUE(std::isnan(eta_seconds(s)));
  EXPECT_EQ(format_terminal_line(s, 10), "[----------]   0.0%  0/4 runs  0/100 ep  - ep/s  ETA --");
}

TEST(SweepProgressReporter, TerminalLineShowsBarRunsRateAndEta) {
  EXPECT_EQ(format_terminal_line(quarter_done(), 20),
            "[#####---------------]  25.0%  10/40 runs  1250/5000 ep  85.3 ep/s  ETA 44s");
}

TEST(SweepProgressReporter, PlainLineShowsElapsedAndEta) {
  EXPECT_EQ(format_plain_line(quarter_done()),
            "progress  25.0% | runs 10/40 | episodes 1250/5000 | 85.3 episodes/s | elapsed 15s | ETA 44s");
}

TEST(SweepProgressReporter, FinalLineSaysDoneOrStopped) {
  const ProgressSnapshot done{.total_runs = 40, .runs_done = 40, .total_episodes = 5000, .episodes_done = 5000,
                              .elapsed_s = 62.0};
  EXPECT_EQ(format_final_line(done), "done: 40/40 runs, 5000/5000 episodes in 1m02s (80.6 episodes/s)");
  EXPECT_EQ(format_final_line(quarter_done()), "stopped: 10/40 runs, 1250/5000 episodes in 15s (85.3 episodes/s)");
}

TEST(SweepProgressReporter, PlainOutputPrintsEachTenthWhenTimeStandsStill) {
  FakeClock clock;
  CapturedFile out;
  {
    ProgressReporter progress(1, 100, out.get(), {.style = ProgressStyle::kPlain, .clock = clock.source()});
    EXPECT_FALSE(progress.terminal());
    for (int i = 0; i < 100; ++i) progress.episode_done();
    progress.run_done();
    progress.finish();
  }
  const std::string text = out.text();
  EXPECT_EQ(count_of(text, "progress "), 10u) << text;  // 10%, 20%, ..., 100%
  EXPECT_EQ(count_of(text, "\n"), 11u) << text;
  EXPECT_NE(text.find("progress  10.0% | runs 0/1 | episodes 10/100"), std::string::npos) << text;
  EXPECT_EQ(count_of(text, "done: 1/1 runs, 100/100 episodes"), 1u) << text;
  EXPECT_EQ(text.find('\r'), std::string::npos);
}

TEST(SweepProgressReporter, PlainOutputPrintsEveryFiveSeconds) {
  FakeClock clock;
  CapturedFile out;
  ProgressReporter progress(1, 1000, out.get(), {.style = ProgressStyle::kPlain, .clock = clock.source()});
  for (int i = 0; i < 12; ++i) {  // 12 episodes, 1 s each: 1.2% of the work, lines at 5 s and 10 s
    clock.now += 1s;
    progress.episode_done();
  }
  const std::string text = out.text();
  EXPECT_EQ(count_of(text, "\n"), 2u) << text;
  EXPECT_NE(text.find("episodes 5/1000 | 1.0 episodes/s | elapsed 5s"), std::string::npos) << text;
  EXPECT_NE(text.find("episodes 10/1000 | 1.0 episodes/s | elapsed 10s"), std::string::npos) << text;
}

TEST(SweepProgressReporter, TerminalOutputRedrawsAtMostEveryInterval) {
  FakeClock clock;
  CapturedFile out;
  {
    ProgressReporter progress(1, 100, out.get(), {.style = ProgressStyle::kTerminal, .clock = clock.source()});
    EXPECT_TRUE(progress.terminal());
    for (int i = 0; i < 100; ++i) {  // 10 ms per episode: one redraw per 100 ms, i.e. every 10th episode
      clock.now += 10ms;
      progress.episode_done();
    }
    progress.run_done();
    progress.finish();
  }
  const std::string text = out.text();
  EXPECT_EQ(count_of(text, "\r["), 10u) << text;
  EXPECT_EQ(count_of(text, "\x1b[K"), 11u) << text;  // each redraw and the final line clear the rest
  EXPECT_EQ(count_of(text, "\n"), 1u) << text;     // only the final line ends the line
  EXPECT_NE(text.find("\r[##------------------]  10.0%  0/1 runs  10/100 ep"), std::string::npos) << text;
  EXPECT_NE(text.find("  20/100 ep  100.0 ep/s  ETA 1s"), std::string::npos) << text;
  EXPECT_NE(text.find("\rdone: 1/1 runs, 100/100 episodes in 1s (100.0 episodes/s)\x1b[K\n"), std::string::npos)
      << text;
}

TEST(SweepProgressReporter, FinishPrintsOnceAndSilencesLaterCounts) {
  FakeClock clock;
  CapturedFile out;
  ProgressReporter progress(2, 0, out.get(), {.style = ProgressStyle::kPlain, .clock = clock.source()});
  progress.finish();
  progress.finish();
  progress.run_done();
  progress.run_done();
  EXPECT_EQ(out.text(), "stopped: 0/2 runs, 0 episodes in 0s (- episodes/s)\n");
  EXPECT_EQ(progress.snapshot().runs_done, 2u);  // still counted
}

TEST(SweepProgressReporter, DestructorEndsAnOpenTerminalLine) {
  FakeClock clock;
  CapturedFile out;
  {
    ProgressReporter progress(1, 10, out.get(), {.style = ProgressStyle::kTerminal, .clock = clock.source()});
    clock.now += 1s;
    progress.episode_done();
  }
  const std::string text = out.text();
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(count_of(text, "\n"), 1u);
}

TEST(SweepProgressReporter, ForcePlainOnANonTerminalFile) {
  CapturedFile out;
  EXPECT_FALSE(ProgressReporter(1, 1, out.get()).terminal());  // a regular file is never a terminal
  EXPECT_FALSE(ProgressReporter(1, 1, out.get(), true).terminal());
}

TEST(SweepProgressReporter, CountsFromManyThreads) {
  FakeClock clock;
  CapturedFile out;
  ProgressReporter progress(64, 64 * 50, out.get(), {.style = ProgressStyle::kPlain, .clock = clock.source()});
  run_indexed(64, 4, [&progress](std::size_t) {
    for (int e = 0; e < 50; ++e) progress.episode_done();
    progress.run_done();
  });
  const ProgressSnapshot s = progress.snapshot();
  EXPECT_EQ(s.episodes_done, 3200u);
  EXPECT_EQ(s.runs_done, 64u);
  EXPECT_EQ(count_of(out.text(), "\n"), 10u);  // one line per tenth, however the threads interleave
}

}  // namespace
}  // namespace peg3d::sweep
