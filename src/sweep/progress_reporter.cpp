#include "sweep/progress_reporter.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <utility>

#include "core/validation.hpp"

namespace peg3d::sweep {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string format_rate(double per_second) {
  return std::isfinite(per_second) ? fmt::format("{:.1f}", per_second) : std::string("-");
}

std::string format_episodes(const ProgressSnapshot& s) {
  return s.total_episodes > 0 ? fmt::format("{}/{}", s.episodes_done, s.total_episodes)
                              : fmt::format("{}", s.episodes_done);
}

bool is_terminal(std::FILE* out) { return out != nullptr && ::isatty(::fileno(out)) == 1; }

}  // namespace

double progress_fraction(const ProgressSnapshot& s) {
  if (s.total_episodes > 0) {
    return std::min(1.0, static_cast<double>(s.episodes_done) / static_cast<double>(s.total_episodes));
  }
  if (s.total_runs > 0) return std::min(1.0, static_cast<double>(s.runs_done) / static_cast<double>(s.total_runs));
  return 1.0;
}

double episodes_per_second(const ProgressSnapshot& s) {
  return s.elapsed_s > 0.0 ? static_cast<double>(s.episodes_done) / s.elapsed_s : kNaN;
}

double eta_seconds(const ProgressSnapshot& s) {
  const double f = progress_fraction(s);
  if (f >= 1.0) return 0.0;
  if (f <= 0.0 || !(s.elapsed_s > 0.0)) return kNaN;
  return s.elapsed_s * (1.0 - f) / f;
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "--";
  if (seconds < 59.5) return fmt::format("{}s", std::lround(seconds));
  if (seconds < 3599.5) {
    const long total = std::lround(seconds);
    return fmt::format("{}m{:02}s", total / 60, total % 60);
  }
  const long minutes = std::lround(seconds / 60.0);
  if (minutes < 24 * 60) return fmt::format("{}h{:02}m", minutes / 60, minutes % 60);
  const long hours = std::lround(seconds / 3600.0);
  return fmt::format("{}d{:02}h", hours / 24, hours % 24);
}

std::string format_terminal_line(const ProgressSnapshot& s, int bar_width) {
  const double f = progress_fraction(s);
  const auto width = static_cast<std::size_t>(std::max(bar_width, 1));
  const auto filled = std::min(width, static_cast<std::size_t>(f * static_cast<double>(width)));
  return fmt::format("[{}{}] {:5.1f}%  {}/{} runs  {} ep  {} ep/s  ETA {}", std::string(filled, '#'),
                     std::string(width - filled, '-'), 100.0 * f, s.runs_done, s.total_runs, format_episodes(s),
                     format_rate(episodes_per_second(s)), format_duration(eta_seconds(s)));
}

std::string format_plain_line(const ProgressSnapshot& s) {
  return fmt::format("progress {:5.1f}% | runs {}/{} | episodes {} | {} episodes/s | elapsed {} | ETA {}",
                     100.0 * progress_fraction(s), s.runs_done, s.total_runs, format_episodes(s),
                     format_rate(episodes_per_second(s)), format_duration(s.elapsed_s),
                     format_duration(eta_seconds(s)));
}

std::string format_final_line(const ProgressSnapshot& s) {
  const bool complete = s.runs_done >= s.total_runs && s.episodes_done >= s.total_episodes;
  return fmt::format("{}: {}/{} runs, {} episodes in {} ({} episodes/s)", complete ? "done" : "stopped",
                     s.runs_done, s.total_runs, format_episodes(s), format_duration(s.elapsed_s),
                     format_rate(episodes_per_second(s)));
}

ProgressReporter::ProgressReporter(std::size_t total_runs, std::size_t total_episodes, std::FILE* out,
                                   bool force_plain)
    : ProgressReporter(total_runs, total_episodes, out,
                       ProgressOptions{.style = force_plain ? ProgressStyle::kPlain : ProgressStyle::kAuto}) {}

ProgressReporter::ProgressReporter(std::size_t total_runs, std::size_t total_episodes, std::FILE* out,
                                   ProgressOptions options)
    : total_runs_(total_runs),
      total_episodes_(total_episodes),
      out_(out),
      options_(std::move(options)),
      terminal_(options_.style == ProgressStyle::kTerminal ||
                (options_.style == ProgressStyle::kAuto && is_terminal(out))) {
  require_at_least("bar_width", options_.bar_width, 1);
  start_ = now();
  last_print_ = start_;
}

ProgressReporter::~ProgressReporter() {
  const std::lock_guard lock(print_mutex_);
  if (line_open_) write("\n");
}

ProgressReporter::TimePoint ProgressReporter::now() const {
  return options_.clock ? options_.clock() : std::chrono::steady_clock::now();
}

ProgressSnapshot ProgressReporter::snapshot_at(TimePoint now) const {
  return {total_runs_, runs_done_.load(), total_episodes_, episodes_done_.load(),
          std::max(0.0, std::chrono::duration<double>(now - start_).count())};
}

ProgressSnapshot ProgressReporter::snapshot() const { return snapshot_at(now()); }

void ProgressReporter::episode_done(std::size_t count) {
  episodes_done_.fetch_add(count);
  maybe_print();
}

void ProgressReporter::run_done() {
  runs_done_.fetch_add(1);
  maybe_print();
}

void ProgressReporter::write(const std::string& text) {
  if (out_ == nullptr) return;
  std::fputs(text.c_str(), out_);
  std::fflush(out_);  // stderr-like streams may be buffered when redirected; a progress line must show now
}

void ProgressReporter::maybe_print() {
  const std::lock_guard lock(print_mutex_);
  if (finished_) return;
  const TimePoint t = now();
  const ProgressSnapshot s = snapshot_at(t);
  if (terminal_) {
    if (t - last_print_ < options_.terminal_interval) return;
    write(fmt::format("\r{}\x1b[K", format_terminal_line(s, options_.bar_width)));  // ESC[K: clear the rest
    line_open_ = true;
  } else {
    const int decile = static_cast<int>(std::floor(10.0 * progress_fraction(s)));
    if (decile <= last_decile_ && t - last_print_ < options_.plain_interval) return;
    write(format_plain_line(s) + "\n");
    last_decile_ = std::max(last_decile_, decile);
  }
  last_print_ = t;
}

void ProgressReporter::finish() {
  const std::lock_guard lock(print_mutex_);
  if (finished_) return;
  finished_ = true;
  const std::string line = format_final_line(snapshot_at(now()));
  write(terminal_ ? fmt::format("\r{}\x1b[K\n", line) : line + "\n");
  line_open_ = false;
}

}  // namespace peg3d::sweep
