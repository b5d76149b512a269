#pragma once
// Standard base64 (RFC 4648, with padding) of raw bytes: how replays (view/replay.hpp) and journals carry arrays of
// numbers compactly and exactly, as their little-endian bytes.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace peg3d {

/// The base64 text of `bytes` bytes at `data`.
std::string base64(const void* data, std::size_t bytes);

/// The bytes of base64 text; throws std::invalid_argument on a length that is not a multiple of 4, a character
/// outside the alphabet or misplaced padding.
std::vector<std::uint8_t> base64_decode(std::string_view text);

}  // namespace peg3d
