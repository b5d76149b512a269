#pragma once
// Result files are never half-written: the content goes to a temporary file beside the target and is
// renamed over it only once it is complete and flushed to disk, so a crash or an exception leaves either
// the previous file or the new one, never a truncated mix. Readers (plot scripts, a resumed sweep) can
// trust any file that exists.

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <ostream>
#include <string_view>

namespace peg3d {

/// A file written through a temporary "<path>.tmp-<pid>-<n>" in the same directory (a rename is atomic only
/// within one file system; n is a per-process counter, so threads writing the same target never share a
/// temporary). Not copyable or movable: the temporary belongs to this object.
class AtomicFile {
 public:
  /// Opens the temporary file for writing (binary: no newline translation). The directory must exist.
  /// Throws std::runtime_error naming the temporary path and the errno text when it cannot be created.
  explicit AtomicFile(std::filesystem::path path);
  /// Removes the temporary file unless commit() succeeded; `path` is then left as it was.
  ~AtomicFile();

  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// The stream to write the content to; valid until commit().
  std::ostream& stream() { return out_; }

  /// Flushes and closes the stream, checks that every write succeeded, syncs the data to disk and renames
  /// the temporary over `path`. Throws std::runtime_error naming the path and the errno text on failure
  /// (`path` is untouched and the destructor removes the temporary); std::logic_error when called twice.
  void commit();

  const std::filesystem::path& path() const noexcept { return path_; }
  const std::filesystem::path& temp_path() const noexcept { return temp_path_; }
  bool committed() const noexcept { return committed_; }

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_path_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Writes `content` to `path` through an AtomicFile. Throws std::runtime_error on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);
/// The chunks one after the other, through one AtomicFile.
void write_file_atomically(const std::filesystem::path& path, std::initializer_list<std::string_view> chunks);

}  // namespace peg3d
