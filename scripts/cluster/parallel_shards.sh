#!/usr/bin/env bash
# One vgroove run split into N shards on one host with GNU parallel (J at a time, each with T
# threads), then merged: the same report as one process (timings aside). Stops at the first failed
# shard (--halt now,fail=1): no report is written.
#
#   scripts/cluster/parallel_shards.sh N J T REPORT -- COMMAND...
#   scripts/cluster/parallel_shards.sh 8 2 1 fig11.json -- build/vgroove validate data/suites/fig11.json
#
# COMMAND is any of `vgroove validate`, `vgroove bench accuracy`, `vgroove simulate`,
# `vgroove energy`, without --out and --shard; the parts go to REPORT's name with .parts/.
set -euo pipefail
if (($# < 6)) || [[ $5 != -- ]]; then
  sed -n '2,11p' "$0" >&2
  exit 2
fi
n=$1 jobs=$2 threads=$3 report=$4
shift 5
for v in "$n" "$jobs"; do
  [[ $v =~ ^[1-9][0-9]*$ ]] || { echo "parallel_shards: N and J must be positive integers, got '$v'" >&2; exit 2; }
done
command -v parallel >/dev/null || { echo "parallel_shards: GNU parallel is not installed (apt-get install parallel)" >&2; exit 2; }
[[ ! -e $report ]] || { echo "parallel_shards: $report exists; move it away first" >&2; exit 2; }
vgroove=$1
parts=${report%.json}.parts
mkdir -p "$parts"
seq 1 "$n" | parallel --will-cite --halt now,fail=1 -j "$jobs" \
  "$(printf '%q ' "$@")" --threads "$threads" --shard "{}/$n" --out "$parts/part-{}.json" --force '>' "$parts/log-{}.txt"
parts_list=()
for ((i = 1; i <= n; ++i)); do parts_list+=("$parts/part-$i.json"); done
"$vgroove" merge "${parts_list[@]}" --out "$report"
