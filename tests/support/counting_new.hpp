#pragma once
// Replaces the global operator new of a test program with one that counts, for tests that check a hot path
// allocates nothing. Include it in exactly one source file of a program: it defines the replacement
// operators, which then apply to the whole program.

#include <atomic>
#include <cstdlib>
#include <new>

namespace peg3d::testing {

/// Allocations so far through operator new (and any hook that adds to it, such as Bullet's allocator).
inline std::atomic<long> g_allocations{0};

}  // namespace peg3d::testing

// The replacement new takes memory from malloc, so free() is the matching release; GCC cannot see that
// once both are inlined into a std::allocator.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t n) {
  ++peg3d::testing::g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// Over-aligned types (alignas above 16, e.g. a map's bit words) come through the aligned forms: counted too.
void* operator new(std::size_t n, std::align_val_t a) {
  ++peg3d::testing::g_allocations;
  const auto align = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(align, (n + align - 1) / align * align)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
