#include "world/file_io.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

namespace peg3d::world {

void write_file_atomically(const std::filesystem::path& file, std::initializer_list<std::string_view> chunks) {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  // Unique per process and call, in the target's folder so that rename() stays on one file system.
  const std::filesystem::path tmp =
      file.string() + fmt::format(".tmp-{}-{}", static_cast<long>(::getpid()), counter.fetch_add(1));
  auto failure = [&](const std::string& what, int err) {
    std::filesystem::remove(tmp, ec);
    return std::runtime_error(fmt::format("cannot write '{}': {}: {}", file.string(), what, std::strerror(err)));
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw failure("open", errno);
  for (std::string_view chunk : chunks) {
    const char* p = chunk.data();
    std::size_t left = chunk.size();
    while (left > 0) {
      const ssize_t n = ::write(fd, p, left);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int err = errno;
        ::close(fd);
        throw failure("write", err);
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    throw failure("fsync", err);
  }
  if (::close(fd) != 0) throw failure("close", errno);
  if (::rename(tmp.c_str(), file.c_str()) != 0) throw failure("rename", errno);
}

}  // namespace peg3d::world
