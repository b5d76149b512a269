#pragma once
// Seeding. One root seed per experiment; every run, agent and generator derives its own seed from it by
// position (never by thread or by wall clock), so results do not depend on how work is scheduled.

#include <cstdint>
#include <initializer_list>
#include <random>

namespace peg3d {

/// The one random engine used everywhere: explicit, portable across runs of the same build.
using Rng = std::mt19937_64;

/// SplitMix64 finaliser: a bijective 64-bit mix with good avalanche.
constexpr std::uint64_t mix64(std::uint64_t x) noexcept {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Seed for the stream identified by `path` below `root`, e.g. derive_seed(root, {scenario, repeat}).
/// Distinct paths give independent-looking seeds; the same path always gives the same seed.
constexpr std::uint64_t derive_seed(std::uint64_t root, std::initializer_list<std::uint64_t> path) noexcept {
  std::uint64_t s = mix64(root);
  for (std::uint64_t p : path) s = mix64(s ^ mix64(p + 0x632BE59BD9B4E019ull));
  return s;
}

/// A uniform number in [0, 1) from the top 53 bits of one output: portable, unlike the std distributions.
inline double unit_uniform(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// Uniform in [lo, hi] from one output, as unit_uniform.
inline double uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * unit_uniform(rng); }

}  // namespace peg3d
