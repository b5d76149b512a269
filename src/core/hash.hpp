#pragma once
// A stable content hash: cache keys of built worlds, and the golden hashes that guard determinism.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace peg3d {

/// 64-bit FNV-1a: the same value on every run, build and platform of the same endianness.
class Fnv1a {
 public:
  void add(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001B3ull;
  }
  /// The object representation of a trivially copyable value (doubles by their bits: -0.0 differs from 0.0).
  template <class T>
  void add_value(const T& value) {
    add(&value, sizeof(T));
  }
  /// Every element's representation, in order (any contiguous range of trivially copyable values).
  template <class Range>
  void add_span(const Range& values) {
    const std::span view(values);
    add(view.data(), view.size_bytes());
  }
  void add_text(std::string_view text) {
    add_value(text.size());
    add(text.data(), text.size());
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xCBF29CE484222325ull;
};

}  // namespace peg3d
