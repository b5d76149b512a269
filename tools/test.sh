#!/usr/bin/env bash
# Builds everything and runs the whole test suite with CTest; exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)" "$@"
