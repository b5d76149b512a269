#include "sweep/distributed_sweep.hpp"

#include <atomic>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <variant>

#include <fmt/format.h>

#include "sweep/parallel_runner.hpp"
#include "sweep/process_group.hpp"
#include "sweep/progress_reporter.hpp"
#include "sweep/run_journal.hpp"

namespace peg3d::sweep {
namespace {

enum class Kind : std::uint8_t { kNothing = 0, kResult = 1, kCancelled = 2, kFailed = 3, kDone = 4 };
constexpr std::uint64_t kNoRun = std::numeric_limits<std::uint64_t>::max();
constexpr std::size_t kHeader = 2 + 8 + 8;

struct Report {
  Kind kind = Kind::kNothing;
  bool wants_more = false;
  std::uint64_t run = 0;
  std::uint64_t episodes = 0;  // counted on the sender since its previous report
  std::string payload;
};

void put_u64(std::string& out, std::uint64_t v) {
  char b[8];
  std::memcpy(b, &v, 8);  // both ends are the same build on the same kind of machine
  out.append(b, 8);
}

std::uint64_t get_u64(const std::string& in, std::size_t at) {
  std::uint64_t v = 0;
  std::memcpy(&v, in.data() + at, 8);
  return v;
}

std::string encode_report(const Report& r) {
  std::string out;
  out.reserve(kHeader + r.payload.size());
  out.push_back(static_cast<char>(r.kind));
  out.push_back(r.wants_more ? 1 : 0);
  put_u64(out, r.run);
  put_u64(out, r.episodes);
  out += r.payload;
  return out;
}

Report decode_report(const GroupMessage& m) {
  if (m.bytes.size() < kHeader || static_cast<std::uint8_t>(m.bytes[0]) > static_cast<std::uint8_t>(Kind::kDone)) {
    throw std::runtime_error(fmt::format("distributed sweep: a malformed report from rank {}", m.from));
  }
  return {static_cast<Kind>(m.bytes[0]), m.bytes[1] != 0, get_u64(m.bytes, 2), get_u64(m.bytes, 10),
          m.bytes.substr(kHeader)};
}

std::string encode_answer(std::optional<std::size_t> run) {
  std::string out;
  put_u64(out, run ? static_cast<std::uint64_t>(*run) : kNoRun);
  return out;
}

std::optional<std::size_t> decode_answer(const GroupMessage& m) {
  if (m.from != 0 || m.bytes.size() != 8) throw std::runtime_error("distributed sweep: a malformed answer from the root");
  const std::uint64_t v = get_u64(m.bytes, 0);
  if (v == kNoRun) return std::nullopt;
  return static_cast<std::size_t>(v);
}

/// The root's list of runs, handed out in order to local threads and remote ranks alike, and the lowest
/// failure seen anywhere.
class Dispenser {
 public:
  Dispenser(const std::vector<std::size_t>& todo, const StopCheck& stop) : todo_(todo), stop_(stop) {}

  std::optional<std::size_t> take() {
    if (failed_.load(std::memory_order_relaxed) || (stop_ && stop_())) return std::nullopt;
    const std::size_t k = next_.fetch_add(1, std::memory_order_relaxed);
    if (k >= todo_.size()) return std::nullopt;
    return todo_[k];
  }

  void fail(std::size_t run, std::exception_ptr error) {
    const std::lock_guard lock(mutex_);
    if (!error_ || run < failed_run_) failed_run_ = run, error_ = std::move(error);
    failed_.store(true, std::memory_order_relaxed);
  }

  void rethrow_failure() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  const std::vector<std::size_t>& todo_;
  const StopCheck& stop_;
  std::atomic<std::size_t> next_{0};
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::size_t failed_run_ = 0;
  std::exception_ptr error_;
};

DistributedOutcome serve_as_root(const std::vector<std::size_t>& todo, int threads, const SweepControl& control,
                                 const SweepRuns& runs) {
  ProcessGroup& group = *control.group;
  Dispenser dispenser(todo, control.stop);
  std::atomic<std::size_t> finished{0};

  // This rank's own threads compute runs while this thread answers the other ranks.
  const auto work = [&] {
    while (const std::optional<std::size_t> i = dispenser.take()) {
      try {
        runs.run(*i);
        if (control.journal) control.journal->record(*i, runs.encode(*i));
        finished.fetch_add(1, std::memory_order_relaxed);
      } catch (const RunCancelled&) {
        // dropped: it reruns on resume
      } catch (...) {
        dispenser.fail(*i, std::current_exception());
      }
    }
  };
  std::vector<std::jthread> pool;
  const int workers = resolve_thread_count(threads);
  for (int t = 0; t < workers; ++t) pool.emplace_back(work);

  std::exception_ptr serve_error;
  try {
    for (int ranks_working = group.size() - 1; ranks_working > 0;) {
      const GroupMessage message = group.receive();
      const Report report = decode_report(message);
      if (control.progress && report.episodes > 0) control.progress->episode_done(report.episodes);
      const auto i = static_cast<std::size_t>(report.run);
      switch (report.kind) {
        case Kind::kResult:
          try {
            const nlohmann::json data = nlohmann::json::parse(report.payload);
            runs.restore(i, data);
            if (control.journal) control.journal->record(i, data);
            finished.fetch_add(1, std::memory_order_relaxed);
            if (control.progress) control.progress->run_done();
          } catch (...) {
            dispenser.fail(i, std::current_exception());
          }
          break;
        case Kind::kFailed:
          dispenser.fail(i, std::make_exception_ptr(std::runtime_error(
                                fmt::format("run {} failed on rank {}: {}", i, message.from, report.payload))));
          break;
        case Kind::kDone:
          --ranks_working;
          break;
        case Kind::kNothing:
        case Kind::kCancelled:
          break;
      }
      if (report.wants_more) group.send(message.from, encode_answer(dispenser.take()));
    }
  } catch (...) {
    // The other ranks may wait on this one: the caller ends the group (ProcessGroup::abort).
    serve_error = std::current_exception();
    dispenser.fail(0, serve_error);
  }
  pool.clear();  // joins
  if (serve_error) std::rethrow_exception(serve_error);
  dispenser.rethrow_failure();
  return {finished.load(), control.stop && control.stop()};
}

DistributedOutcome work_for_root(int threads, const SweepControl& control, const SweepRuns& runs) {
  ProcessGroup& group = *control.group;
  std::mutex link;  // one report and its answer at a time on this rank
  std::size_t episodes_sent = 0;
  std::atomic<std::size_t> finished{0};
  std::atomic<bool> stopped{false};

  // Sends a report (with the episodes counted since the last one) and, when it wants more, returns the answer.
  const auto exchange = [&](Report report) -> std::optional<std::size_t> {
    const std::lock_guard lock(link);
    if (control.progress) {
      const std::size_t now = control.progress->snapshot().episodes_done;
      report.episodes = now - episodes_sent;
      episodes_sent = now;
    }
    const bool wants_more = report.wants_more;
    group.send(0, encode_report(report));
    if (!wants_more) return std::nullopt;
    return decode_answer(group.receive());
  };

  const auto work = [&] {
    Report report;  // the previous run's outcome goes with the next request
    for (;;) {
      report.wants_more = !(control.stop && control.stop());
      if (!report.wants_more) stopped.store(true);
      const std::optional<std::size_t> i = exchange(std::move(report));
      if (!i) return;
      report = Report{};
      report.run = *i;
      try {
        runs.run(*i);
        report.payload = runs.encode(*i).dump();
        report.kind = Kind::kResult;
        finished.fetch_add(1, std::memory_order_relaxed);
      } catch (const RunCancelled&) {
        report.kind = Kind::kCancelled;
      } catch (const std::exception& e) {
        report.kind = Kind::kFailed;
        report.payload = e.what();
      } catch (...) {
        report.kind = Kind::kFailed;
        report.payload = "an unexpected failure";
      }
    }
  };
  {
    std::vector<std::jthread> pool;
    const int workers = resolve_thread_count(threads);
    for (int t = 0; t < workers; ++t) pool.emplace_back(work);
  }
  Report done;
  done.kind = Kind::kDone;
  exchange(std::move(done));
  return {finished.load(), stopped.load()};
}

}  // namespace

DistributedOutcome run_distributed(const std::vector<std::size_t>& todo, int threads, const SweepControl& control,
                                   const SweepRuns& runs) {
  if (!control.group || control.group->size() < 2) {
    throw std::logic_error("run_distributed: needs a group of at least two processes");
  }
  if (control.group->is_root()) return serve_as_root(todo, threads, control, runs);
  return work_for_root(threads, control, runs);
}

}  // namespace peg3d::sweep
