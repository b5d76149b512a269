#!/usr/bin/env bash
# Builds everything and runs the whole test suite with CTest; exits non-zero on any failure.
#   tools/test.sh [CTEST ARGS]             Release build in build/
#   tools/test.sh --sanitize [CTEST ARGS]  the same suite under AddressSanitizer and UndefinedBehaviorSanitizer,
#                                          in a build folder of its own (build-sanitize/; asserts on, -O1)
#   tools/test.sh --tsan [CTEST ARGS]      the tests of thread pools (label threads) under ThreadSanitizer, in
#                                          build-tsan/ (asserts on, -O1); builds only their programs
#   tools/test.sh --python-versions        after tools/test.sh: the package's wheel (from build/, nothing
#                                          compiled again) in two clean environments, with the newest numpy,
#                                          gymnasium and pettingzoo from PyPI (tests/python, those needing
#                                          PyTorch skipped) and with the oldest that pyproject.toml accepts
#                                          (tests/python/check_versions.py)
set -euo pipefail
cd "$(dirname "$0")/.."

# configure_sanitized DIR SANITIZERS: the sanitized builds' configuration (once per folder). Benchmarks are timed,
# never checked: they are left out. Warnings are the Release build's check (-Werror there); GCC 12 at -O1 with
# ASan warns falsely inside <regex> (maybe-uninitialized), so here they stay warnings. -g1: line tables for the
# sanitizers' stack traces, without the variables' debug information that cost a quarter of the compile time. A
# unity build (CMake compiles each target's sources eight to a unit): every header is parsed and every template
# instantiated once a unit, not once a file; a developer's Release build/ compiles file by file, which is what
# catches a file that misses an include.
configure_sanitized() {
  if [[ ! -f $1/CMakeCache.txt ]]; then
    cmake -S . -B "$1" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
          -DPEG3D_SANITIZE="$2" -DPEG3D_BUILD_BENCHMARKS=OFF -DPEG3D_WERROR=OFF -DCMAKE_UNITY_BUILD=ON >/dev/null
  fi
}

if [[ "${1:-}" == "--sanitize" ]]; then
  shift
  tools/deps.sh --test
  configure_sanitized build-sanitize "address;undefined"  # everything tested is built
  cmake --build build-sanitize --parallel "$(nproc)" >&2
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  ctest --test-dir build-sanitize --output-on-failure --parallel "$(nproc)" "$@"
  exit
fi
if [[ "${1:-}" == "--tsan" ]]; then
  shift
  tools/deps.sh  # these tests need nothing of the suite's extras (no browser, no Python)
  # The whole library is instrumented (a race inside it shows only then), but only the programs of target
  # peg3d_thread_tests are built.
  configure_sanitized build-tsan thread
  cmake --build build-tsan --parallel "$(nproc)" --target peg3d_thread_tests >&2
  # The first race ends the program (status 66), so its test fails.
  export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
  ctest --test-dir build-tsan --output-on-failure --parallel "$(nproc)" -L threads "$@"
  exit
fi
if [[ "${1:-}" == "--python-versions" ]]; then
  tools/python_env.sh
  rm -rf build/wheel build/venv-newest build/venv-oldest
  .venv/bin/python -m pip wheel --quiet --no-build-isolation --no-deps --config-settings=build-dir=build \
      -w build/wheel . >&2
  wheel=$(ls build/wheel/peg3d-*.whl)
  for which in newest oldest; do
    venv=build/venv-$which
    /usr/bin/python3 -m venv "$venv"  # no system packages: what a newcomer's clean environment has
    if [[ $which == newest ]]; then
      pins=(--upgrade numpy gymnasium pettingzoo)
    else  # the lower bounds of pyproject.toml's dependencies, exactly
      pins=($(sed -n 's/^dependencies = \[\(.*\)\]/\1/p' pyproject.toml | tr -d '" ' | tr , '\n' | sed 's/>=/==/' | tr '\n' ' '))
    fi
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "$wheel" pytest pytest-xdist hypothesis \
        cloudpickle "${pins[@]}" >&2
    "$venv/bin/python" -c 'import numpy, gymnasium, pettingzoo; print("'"$which"': numpy", numpy.__version__,
        "gymnasium", gymnasium.__version__, "pettingzoo", pettingzoo.__version__)'
    if [[ $which == newest ]]; then
      # The installed package (no PYTHONPATH), run from the tests' folder as CTest runs them; on every core
      # (pytest-xdist), as CTest runs its files side by side.
      (cd tests/python && env -u PYTHONPATH -u PEG3D_DATA_DIR "../../$venv/bin/python" -m pytest -q -p no:cacheprovider \
          -n "$(nproc)" .)
    else
      (cd build && env -u PYTHONPATH -u PEG3D_DATA_DIR "venv-oldest/bin/python" ../tests/python/check_versions.py)
    fi
  done
  exit
fi
tools/deps.sh --test
tools/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)" "$@"
