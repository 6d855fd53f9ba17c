#!/usr/bin/env bash
# Sets up, builds everything and runs the default test suite (a few minutes at most on 2 cores).
#   scripts/test.sh             Release build in build/
#   scripts/test.sh --sanitize  the same tests built with AddressSanitizer and UBSan in build-asan/
# Long statistical runs carry the ctest label "long" and are left out; run them with
#   ctest --test-dir build -L long --output-on-failure
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ ${1:-} == --sanitize ]]; then
  export VGROOVE_BUILD_DIR=build-asan
  export VGROOVE_CMAKE_ARGS="-DVGROOVE_SANITIZE=ON -DVGROOVE_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fi
scripts/setup.sh
ctest --test-dir "${VGROOVE_BUILD_DIR:-build}" -LE long --output-on-failure -j "$(nproc)"
