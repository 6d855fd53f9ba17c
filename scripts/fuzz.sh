#!/usr/bin/env bash
# Fuzzes the suite and scene JSON loaders, the command-line parser and `vgroove merge`'s reading of
# shard parts (part_merge_fuzz: fuzz/part_merge.h, seeded with the real parts of tests/fuzz/parts/)
# with libFuzzer (clang, with ASan and UBSan) for SECONDS each (default 60); the report files
# `vgroove plot` reads (target report_plot: scripts/fuzz_reports.py, a deterministic mutation
# fuzzer of plot.py's checks and drawing; Debian's python3 with python3-matplotlib); and the Python
# module's entry points under an address-space limit (target python_entry: scripts/fuzz_python.py,
# the module from build/python, built first). New interesting inputs are kept in
# tests/fuzz/corpus/TARGET; a finding (crash, hang, sanitizer report, uncaught exception) stops
# with a non-zero exit and leaves the input as crash-*/timeout-* in the build-fuzz directory
# (finding-*.json in the current directory for the two Python targets).
#   scripts/fuzz.sh [SECONDS] [TARGET...]        e.g. scripts/fuzz.sh 600, scripts/fuzz.sh 600 report_plot
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(suite_loader_fuzz scene_loader_fuzz cli_fuzz part_merge_fuzz)

if [[ " ${targets[*]} " == *" python_entry "* ]]; then
  scripts/setup.sh _vgroove
  echo "fuzz: python_entry for $secs s (corpus tests/fuzz/corpus/python_entry)" >&2
  PYTHONPATH=build/python /usr/bin/python3 scripts/fuzz_python.py --seconds "$secs"
  rest=()
  for t in "${targets[@]}"; do [[ $t == python_entry ]] || rest+=("$t"); done
  ((${#rest[@]})) || exit 0
  targets=("${rest[@]}")
fi

if [[ " ${targets[*]} " == *" report_plot "* ]]; then
  scripts/install-deps.sh
  echo "fuzz: report_plot for $secs s (corpus tests/fuzz/corpus/report_plot)" >&2
  /usr/bin/python3 scripts/fuzz_reports.py --seconds "$secs"
  rest=()
  for t in "${targets[@]}"; do [[ $t == report_plot ]] || rest+=("$t"); done
  ((${#rest[@]})) || exit 0
  targets=("${rest[@]}")
fi
scripts/install-deps.sh clang libclang-rt-14-dev
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
      -DVGROOVE_FUZZ=ON -DVGROOVE_BUILD_TESTS=OFF -DVGROOVE_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz --target "${targets[@]}" >&2
for t in "${targets[@]}"; do
  corpus=tests/fuzz/corpus/$t
  mkdir -p "$corpus"
  seeds=()
  [[ $t == suite_loader_fuzz ]] && seeds=(data/suites)
  [[ $t == scene_loader_fuzz ]] && seeds=(data/scenes)
  [[ $t == part_merge_fuzz ]] && seeds=(tests/fuzz/parts)
  echo "fuzz: $t for $secs s (corpus $corpus)" >&2
  (cd build-fuzz && ./"$t" -max_total_time="$secs" -timeout=10 -rss_limit_mb=4096 -close_fd_mask=3 \
      -print_final_stats=1 "../$corpus" "${seeds[@]/#/../}")
done
