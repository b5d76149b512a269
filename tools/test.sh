#!/usr/bin/env bash
# Builds everything and runs the whole test suite with CTest; exits non-zero on any failure.
#   tools/test.sh [CTEST ARGS]             Release build in build/
#   tools/test.sh --sanitize [CTEST ARGS]  the same suite under AddressSanitizer and UndefinedBehaviorSanitizer,
#                                          in a build folder of its own (build-sanitize/; asserts on, -O1)
#   tools/test.sh --tsan [CTEST ARGS]      the tests of thread pools (label threads) under ThreadSanitizer, in
#                                          build-tsan/ (asserts on, -O1); builds only their programs
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${1:-}" == "--sanitize" ]]; then
  shift
  tools/deps.sh --test
  if [[ ! -f build-sanitize/CMakeCache.txt ]]; then
    # Benchmarks are timed, never checked: the sanitized build leaves them out and builds everything tested.
    # Warnings are the Release build's check (-Werror there); GCC 12 at -O1 with ASan warns falsely inside
    # <regex> (maybe-uninitialized), so here they stay warnings.
    cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
          -DPEG3D_SANITIZE="address;undefined" -DPEG3D_BUILD_BENCHMARKS=OFF -DPEG3D_WERROR=OFF >/dev/null
  fi
  cmake --build build-sanitize --parallel "$(nproc)" >&2
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  ctest --test-dir build-sanitize --output-on-failure --parallel "$(nproc)" "$@"
  exit
fi
if [[ "${1:-}" == "--tsan" ]]; then
  shift
  tools/deps.sh  # these tests need nothing of the suite's extras (no browser, no Python)
  if [[ ! -f build-tsan/CMakeCache.txt ]]; then
    # As --sanitize: no benchmarks, warnings not errors. The whole library is instrumented (a race inside it
    # shows only then), but only the programs of target peg3d_thread_tests are built.
    cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
          -DPEG3D_SANITIZE=thread -DPEG3D_BUILD_BENCHMARKS=OFF -DPEG3D_WERROR=OFF >/dev/null
  fi
  cmake --build build-tsan --parallel "$(nproc)" --target peg3d_thread_tests >&2
  # The first race ends the program (status 66), so its test fails.
  export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
  ctest --test-dir build-tsan --output-on-failure --parallel "$(nproc)" -L threads "$@"
  exit
fi
tools/deps.sh --test
tools/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)" "$@"
