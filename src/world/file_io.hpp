#pragma once
// Small file helpers for the world's outputs: a stable content hash and crash-safe writes.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string_view>

namespace peg3d::world {

/// 64-bit FNV-1a: stable across runs, builds and platforms of the same endianness.
class Fnv1a {
 public:
  void add(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001B3ull;
  }
  template <class T>
  void add_value(const T& value) {
    add(&value, sizeof(T));
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xCBF29CE484222325ull;
};

/// Writes the chunks, in order, to a temporary file next to `file`, flushes it to disk and renames it over
/// `file`: readers see the old file or the whole new one, never a part. Creates missing parent folders.
/// Throws std::runtime_error naming the file on failure (and removes the temporary file).
void write_file_atomically(const std::filesystem::path& file, std::initializer_list<std::string_view> chunks);

}  // namespace peg3d::world
