#!/usr/bin/env bash
# The main job: builds what is missing, then runs peg-paper (the paper's experiment, results in
# results/paper/). Extra arguments go to peg-paper, e.g. tools/run.sh --repeats 5 --out results/quick.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
# One replay viewer per paper scenario (the peg3d algorithm) beside the figures: --html.
exec build/bin/peg-paper --html '*_peg3d' "$@"
