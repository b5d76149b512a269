#!/usr/bin/env bash
# Installs missing packages, then configures (once) and builds Release into build/. Incremental on reruns.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/deps.sh
if [[ ! -f build/CMakeCache.txt ]]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPEG3D_WERROR=ON >/dev/null
fi
cmake --build build --parallel "$(nproc)" >&2  # build log on stderr: stdout is the program's
