#!/usr/bin/env bash
# Installs what is missing (Debian packages), then configures and builds vgroove in build/.
# Idempotent: with everything installed and built it only checks, in a second or two.
#   scripts/setup.sh [TARGET...]    (no target: build everything, tests and benchmarks included)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake ninja-build git libeigen3-dev libcli11-dev nlohmann-json3-dev
          libgtest-dev libgmock-dev libbenchmark-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [[ $(id -u) -ne 0 ]]; then
    echo "setup: missing packages: ${missing[*]}; run as root (or: sudo apt-get install ${missing[*]})" >&2
    exit 1
  fi
  echo "setup: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

build=${VGROOVE_BUILD_DIR:-build}
# Configuring again is cheap and keeps the options right for a build dir made by hand.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVGROOVE_BUILD_TESTS=ON -DVGROOVE_BUILD_BENCH=ON \
      ${VGROOVE_CMAKE_ARGS:-} >/dev/null
if (($#)); then
  cmake --build "$build" --target "$@" >&2
else
  cmake --build "$build" >&2
fi
