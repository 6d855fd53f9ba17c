#!/usr/bin/env bash
# Installs what is missing (Debian packages), then configures and builds vgroove in build/.
# Idempotent: with everything installed and built it only checks, in a second or two.
#   scripts/setup.sh [TARGET...]    (no target: build everything, tests and benchmarks included)
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh

build=${VGROOVE_BUILD_DIR:-build}
# Configuring again is cheap and keeps the options right for a build dir made by hand.
# VGROOVE_CMAKE_ARGS comes last, so it can override these (scripts/test.sh --sanitize does).
# The Python module is built for Debian's interpreter, /usr/bin/python3, whose dist-packages hold
# numpy, matplotlib and pytest (a python3 earlier on PATH, e.g. a pyenv one, does not); use it as
#   PYTHONPATH=$build/python /usr/bin/python3 -c "import vgroove"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVGROOVE_BUILD_TESTS=ON -DVGROOVE_BUILD_BENCH=ON \
      -DVGROOVE_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3 ${VGROOVE_CMAKE_ARGS:-} >/dev/null
if (($#)); then
  cmake --build "$build" --target "$@" >&2
else
  cmake --build "$build" >&2
fi
