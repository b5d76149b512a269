#pragma once

// Whether this test program is built with sanitizers (tools/test.sh --sanitize or --tsan). There, where a test
// repeats one check over many cases (scenarios, games) and its running time is those cases', it plays fewer of
// them: every code path still runs instrumented, and the Release suite plays every case.
namespace peg3d::testing {

#ifdef PEG3D_TESTS_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// `release` in a Release build, `sanitized` in a sanitized one.
constexpr int release_or_sanitized(int release, int sanitized) { return kSanitized ? sanitized : release; }

}  // namespace peg3d::testing
