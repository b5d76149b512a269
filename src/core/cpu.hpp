#pragma once
// What the processor the program runs on can do, asked once: code built for every x86-64 takes wider vector
// lanes where they exist, with the same answers (each lane does the scalar code's float arithmetic).

namespace peg3d {

/// Whether the processor has AVX2 (always false off x86).
inline bool cpu_has_avx2() {
#if defined(__x86_64__) || defined(__i386__)
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
#else
  return false;
#endif
}

}  // namespace peg3d
