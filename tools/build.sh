#!/usr/bin/env bash
# Installs missing packages and the Python environment (.venv), then configures (once) and builds Release into
# build/, and installs the Python package into .venv. Incremental on reruns.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/deps.sh
tools/python_env.sh  # .venv: the Python module is built for its interpreter, and its tests run in it
if [[ ! -f build/CMakeCache.txt ]]; then
  # PEG3D_UNITY_BUILD=ON (set by .ci/run): the library, tools and experiments compiled eight sources to a unit as
  # well, as the test programs always are. Not the default: file by file is what catches a missing include.
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPEG3D_WERROR=ON \
        -DCMAKE_UNITY_BUILD="${PEG3D_UNITY_BUILD:-OFF}" >/dev/null
fi
cmake --build build --parallel "$(nproc)" >&2  # build log on stderr: stdout is the program's
tools/python_env.sh --package  # pip install . into .venv, from build/: nothing is compiled again
