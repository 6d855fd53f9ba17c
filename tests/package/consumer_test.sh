#!/usr/bin/env bash
# Installs vgroove from the build tree BUILD into a fresh prefix, then configures, builds and runs
# examples/cmake-consumer against that prefix alone: a broken export, a missing header or a
# dependency the package does not find again fails here.
#   tests/package/consumer_test.sh BUILD SOURCE
set -euo pipefail
build=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
# The modules' detail/ headers (what only their own sources include) are not installed, and the
# installed headers compile without them: the consumer below includes the public ones.
if find "$work/prefix/include/vgroove" -path '*/detail*' | grep -q .; then
  echo "installed detail headers:" >&2
  find "$work/prefix/include/vgroove" -path '*/detail*' >&2
  exit 1
fi
cmake -S "$src/examples/cmake-consumer" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/vgroove_consumer"
