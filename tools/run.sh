#!/usr/bin/env bash
# The main job: builds what is missing, then runs peg-paper (the paper's experiment, results in
# results/paper/). Extra arguments go to peg-paper, e.g. tools/run.sh --repeats 5 --out results/quick.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
exec build/bin/peg-paper "$@"
