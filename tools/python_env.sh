#!/usr/bin/env bash
# The project's Python environment, .venv: Python 3.11 from Debian with the system's packages visible (numpy and
# pytest from tools/deps.sh), and from PyPI at the versions of python/constraints.txt: gymnasium, pettingzoo, the
# build backend and pybind11, moviepy (for Gymnasium's RecordVideo), PyTorch (CPU), Stable-Baselines3,
# SuperSuit and Ray (peg3d.selfplay's clusters). Fast when they are there.
#   tools/python_env.sh            create it or bring it up to date
#   tools/python_env.sh --package  then build and install peg3d into it (pip install ., from the tree build/)
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ ! -x .venv/bin/python ]]; then
  /usr/bin/python3 -m venv --system-site-packages .venv
fi
want=$(sha256sum python/constraints.txt pyproject.toml | sha256sum | cut -c1-16)
if [[ "$(cat .venv/.peg3d-constraints 2>/dev/null)" != "$want" ]]; then
  .venv/bin/python -m pip install --quiet --disable-pip-version-check -c python/constraints.txt \
      gymnasium pettingzoo scikit-build-core pybind11 moviepy torch stable-baselines3 supersuit ray >&2
  echo "$want" > .venv/.peg3d-constraints
fi
if [[ "${1:-}" == "--package" ]]; then
  # No build isolation: the backend is the one just installed; the build tree is build/, tools/build.sh's (a pip
  # install by hand builds in build/pip: pyproject.toml).
  .venv/bin/python -m pip install --quiet --disable-pip-version-check --no-build-isolation --no-deps \
      --config-settings=build-dir=build . >&2
fi
