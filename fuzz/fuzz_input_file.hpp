#pragma once
// The loaders read files, so each fuzz input is written to one scratch file (in /dev/shm when there is one:
// no disk traffic at tens of thousands of executions a second) and its path handed to the loader.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace peg3d::fuzz {

/// Writes `size` bytes to a scratch file named `name` (its extension chooses the mesh importer) and returns
/// its path; the same path for the same name in one process.
inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path base = std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
    const auto d = base / ("peg3d-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const auto file = dir / name;
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace peg3d::fuzz
