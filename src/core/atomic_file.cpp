#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <fmt/format.h>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace peg3d {
namespace {

std::string errno_text(int error) {
  return error == 0 ? std::string("unknown error") : std::generic_category().message(error);
}

[[noreturn]] void fail(std::string_view what, const std::filesystem::path& path, int error) {
  throw std::runtime_error(fmt::format("{} '{}': {}", what, path.string(), errno_text(error)));
}

// Data must reach the disk before the rename: otherwise a power loss can leave the new name pointing at an
// empty file on file systems with delayed allocation.
void sync_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("cannot open for syncing", path, errno);
  const int synced = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (synced != 0) fail("cannot sync", path, error);
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path path)
    : path_(std::move(path)) {
  static std::atomic<unsigned long> counter{0};
  temp_path_ = fmt::format("{}.tmp-{}-{}", path_.string(), static_cast<long>(::getpid()), counter.fetch_add(1));
  errno = 0;
  out_.open(temp_path_, std::ios::out | std::ios::binary | std::ios::trunc);
  if (!out_.is_open()) fail("cannot create temporary file", temp_path_, errno);
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;  // nothing useful to do about a failed clean-up in a destructor
  std::filesystem::remove(temp_path_, ignored);
}

void AtomicFile::commit() {
  if (committed_) throw std::logic_error(fmt::format("AtomicFile '{}' committed twice", path_.string()));
  errno = 0;
  out_.flush();
  if (!out_) fail("cannot write", temp_path_, errno);
  out_.close();
  if (!out_) fail("cannot close", temp_path_, errno);
  sync_file(temp_path_);
  std::error_code ec;
  std::filesystem::rename(temp_path_, path_, ec);
  if (ec) {
    throw std::runtime_error(
        fmt::format("cannot rename '{}' to '{}': {}", temp_path_.string(), path_.string(), ec.message()));
  }
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path, {content});
}

void write_file_atomically(const std::filesystem::path& path, std::initializer_list<std::string_view> chunks) {
  AtomicFile file(path);
  for (const std::string_view chunk : chunks) file.stream().write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
  file.commit();
}

}  // namespace peg3d
