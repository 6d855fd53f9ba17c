#!/usr/bin/env bash
# Formats every C++ file of the tree with the checked-in .clang-format (clang-format 14), or with
# --check only reports what differs and exits non-zero (CI runs the check).
#   scripts/format.sh [--check]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh clang-format-14
mapfile -t files < <(git ls-files '*.h' '*.cpp' | grep -v '^tests/fuzz/corpus/')
if [[ ${1:-} == --check ]]; then
  clang-format-14 --dry-run -Werror "${files[@]}"
else
  clang-format-14 -i "${files[@]}"
fi
