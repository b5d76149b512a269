#pragma once
// OctoMap's computeRayKeys for a scan's rays, several rays at a time (issue 53, part 1).
//
// The traversal (Amanatides and Woo's, as OcTreeBaseImpl::computeRayKeys steps it) takes, at each step, the axis
// whose next border comes first, and which axis that is changes from step to step without a pattern a branch
// predictor can learn: one ray at a time, a step costs a mispredicted branch about every other cell. Here the
// rays of a scan are stepped eight at a time in two sets of four vector lanes (AVX2, where the processor has it),
// each lane choosing its axis with masks: the same double additions and comparisons in the same order per ray, so
// each ray meets exactly OctoMap's keys. Without AVX2 the rays are stepped one at a time, with the same answers.

#include <cstddef>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

namespace octomath {
class Vector3;
}  // namespace octomath
namespace octomap {
class OcTree;
}  // namespace octomap

namespace peg3d::sense {

/// How trace_rays steps the rays.
enum class RayLanes {
  kBest,    ///< in vector lanes when the processor has AVX2, else one at a time
  kScalar,  ///< one ray at a time
  kVector,  ///< in vector lanes; trace_rays throws std::invalid_argument where vector_lanes_available() is false
};

/// Whether this processor can step rays in vector lanes (AVX2).
bool vector_lanes_available();

/// The keys one ray met, in order: keys[offset + i * stride] for i < count.
struct RayKeySpan {
  std::uint32_t offset = 0, stride = 1, count = 0;
};

/// A cell's key packed in one word: each axis's key plus kKeyBias in 21 bits (x lowest), so that a step of one
/// cell either way never borrows from or carries into the next axis.
inline constexpr std::uint64_t kKeyBias = std::uint64_t{1} << 19;
inline constexpr std::uint64_t kKeyMask = (std::uint64_t{1} << 21) - 1;
inline std::uint16_t packed_key(std::uint64_t word, int axis) {
  return std::uint16_t(((word >> (21 * axis)) & kKeyMask) - kKeyBias);
}

/// The most keys computeRayKeys gives for a ray of `length` m at `resolution` m: each axis steps while its border
/// lies within the length, at most length |direction(i)| / resolution + 1 times, and a few more for rounding.
inline std::size_t ray_keys_most(double length, double resolution) {
  return std::size_t(std::numbers::sqrt3 * length / resolution) + 8;
}
/// The room (words of keys) trace_rays needs for `rays` rays of at most `range` m: per group of eight rays, as
/// many rows as the longest one's keys and one more, and one for a length rounded up to float.
inline std::size_t trace_room(std::size_t rays, double range, double resolution) {
  return (rays + 7) / 8 * 8 * (ray_keys_most(range, resolution) + 2);
}

/// For each ray from `origin` to ends[i], the keys OctoMap's tree.computeRayKeys(origin, ends[i], ...) gives
/// (nothing when it fails: an end beyond the keys' range, or both ends in one cell), packed, into keys, and where
/// they are into spans[i] (in vector lanes a ray's keys lie `stride` apart). keys' size is its room: it is resized
/// (doubling) only when the rays need more than it has, and its words past the returned count mean nothing.
/// Returns the words of keys used.
std::size_t trace_rays(const octomap::OcTree& tree, const octomath::Vector3& origin,
                       std::span<const octomath::Vector3> ends, std::vector<std::uint64_t>& keys,
                       std::vector<RayKeySpan>& spans, RayLanes lanes = RayLanes::kBest);

}  // namespace peg3d::sense
