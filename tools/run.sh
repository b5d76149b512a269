#!/usr/bin/env bash
# The main job: builds what is missing, then runs it. Extra arguments go to the program.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
exec build/bin/peg-apollonius "$@"
