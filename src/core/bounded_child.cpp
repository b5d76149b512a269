#include "core/bounded_child.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <new>
#include <optional>
#include <stdexcept>

#if defined(__SANITIZE_ADDRESS__)
#define PEG3D_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PEG3D_ASAN 1
#endif
#endif

namespace peg3d {
namespace {

// Pages of a process's address space and of its resident set, from /proc/PID/statm (0, 0 if unreadable).
struct Statm {
  std::size_t size = 0, resident = 0;
};
Statm statm(pid_t pid) {
  char path[64];
  std::snprintf(path, sizeof path, "/proc/%d/statm", static_cast<int>(pid));
  Statm s;
  if (FILE* f = std::fopen(path, "r")) {
    if (std::fscanf(f, "%zu %zu", &s.size, &s.resident) != 2) s = {};
    std::fclose(f);
  }
  return s;
}

void write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return;
    data += w;
    n -= static_cast<std::size_t>(w);
  }
}

[[noreturn]] void child(int fd, const std::function<std::string()>& work, const ChildLimits& limits, std::size_t vm) {
  rlimit none{0, 0};
  ::setrlimit(RLIMIT_CORE, &none);  // a crash here is expected, not something to dump
#ifndef PEG3D_ASAN
  rlimit as{vm + limits.extra_memory_bytes, vm + limits.extra_memory_bytes};
  ::setrlimit(RLIMIT_AS, &as);
#else
  (void)vm, (void)limits;  // ASan reserves terabytes of address space: the parent's RSS watch stands in
#endif
  char status = 'F';
  std::string out;
  try {
    out = work();
    status = 'O';
  } catch (const std::bad_alloc&) {
    status = 'M';
    out.clear();
  } catch (const std::exception& e) {
    out = e.what();
  } catch (...) {
    out = "unknown error";
  }
  write_all(fd, &status, 1);
  write_all(fd, out.data(), out.size());
  ::_exit(0);
}

}  // namespace

ChildResult run_bounded(const std::function<std::string()>& work, const ChildLimits& limits) {
  const long page = ::sysconf(_SC_PAGESIZE);
  const Statm self = statm(::getpid());
  const std::size_t vm = self.size * static_cast<std::size_t>(page);
  const std::size_t rss_limit = self.resident * static_cast<std::size_t>(page) + limits.extra_memory_bytes;

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], work, limits, vm);
  }
  ::close(fds[1]);

  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(limits.seconds * ChildLimits::kWallTimeFactor));
  clockid_t child_cpu{};
  const bool have_cpu_clock = ::clock_getcpuclockid(pid, &child_cpu) == 0;
  // Out of time: used its processor seconds (kTimedOut), or blocked for the wall-clock backstop (kBlocked).
  const auto out_of_time = [&]() -> std::optional<ChildResult::Status> {
    timespec used{};
    if (have_cpu_clock && ::clock_gettime(child_cpu, &used) == 0 &&
        double(used.tv_sec) + 1e-9 * double(used.tv_nsec) > limits.seconds) {
      return ChildResult::Status::kTimedOut;
    }
    if (Clock::now() > deadline) return ChildResult::Status::kBlocked;
    return std::nullopt;
  };
  ChildResult result;
  std::string bytes;
  bool killed = false;
  const auto kill_with = [&](ChildResult::Status why) {
    ::kill(pid, SIGKILL);
    result.status = why;
    killed = true;
  };
  char buffer[1 << 16];
  while (!killed) {
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, 20);  // also the period of the memory watch
    if (ready < 0 && errno != EINTR) break;
    if (ready > 0) {
      const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;  // EOF: the child is leaving
      bytes.append(buffer, static_cast<std::size_t>(n));
      if (bytes.size() > limits.extra_memory_bytes) kill_with(ChildResult::Status::kOutOfMemory);
    }
    if (statm(pid).resident * static_cast<std::size_t>(page) > rss_limit) kill_with(ChildResult::Status::kOutOfMemory);
    else if (const auto why = out_of_time()) kill_with(*why);
  }
  ::close(fds[0]);
  int wstatus = 0;
  // After EOF the child only has _exit left; the deadline still holds in case it does not.
  for (;;) {
    const pid_t r = ::waitpid(pid, &wstatus, killed ? 0 : WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) break;
    if (r == 0) {
      if (const auto why = out_of_time()) kill_with(*why);
      else ::usleep(1000);
    }
  }
  if (killed) return result;
  if (WIFSIGNALED(wstatus)) {
    result.status = ChildResult::Status::kCrashed;
    result.output = ::sigabbrev_np(WTERMSIG(wstatus)) != nullptr ? std::string("SIG") + ::sigabbrev_np(WTERMSIG(wstatus))
                                                                   : "signal " + std::to_string(WTERMSIG(wstatus));
    return result;
  }
  if (bytes.empty()) {
    result.status = ChildResult::Status::kCrashed;
    // A sanitizer's deadly-signal handler turns a crash into an exit, so the status is all there is to say.
    result.output = "exited with status " + std::to_string(WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1) +
                    " without a result";
    return result;
  }
  result.status = bytes[0] == 'O'   ? ChildResult::Status::kOk
                  : bytes[0] == 'M' ? ChildResult::Status::kOutOfMemory
                                    : ChildResult::Status::kFailed;
  result.output = bytes.substr(1);
  return result;
}

}  // namespace peg3d
