#!/usr/bin/env bash
# Installs the Debian 12 packages peg3d needs, only those missing. Fast when everything is present.
#   tools/deps.sh          what building and running needs
#   tools/deps.sh --test   that, plus what the test suite alone needs (headless Chromium for the viewer test)
set -euo pipefail

PACKAGES=(
  g++ cmake ninja-build pkg-config
  libbullet-dev libeigen3-dev libassimp-dev liboctomap-dev libdynamicedt3d-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libboost-dev libmeshoptimizer-dev libjs-three libopenmpi-dev openmpi-bin libembree-dev
  python3-matplotlib python3-numpy python3-scipy python3-dev python3-venv python3-pip
)
if [[ "${1:-}" == "--test" ]]; then
  PACKAGES+=(chromium python3-websocket python3-pil python3-pytest python3-hypothesis)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "peg3d: installing missing Debian packages: ${missing[*]}" >&2
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
