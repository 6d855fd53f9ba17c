#!/usr/bin/env bash
# Sets up, builds everything and runs the default test suite (a few minutes at most on 2 cores).
# Long statistical runs carry the ctest label "long" and are left out; run them with
#   ctest --test-dir build -L long --output-on-failure
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
ctest --test-dir "${VGROOVE_BUILD_DIR:-build}" -LE long --output-on-failure -j "$(nproc)"
