#!/usr/bin/env bash
# What splitting costs and gains on this host (timings: medians of interleaved repetitions; on a
# shared host say so beside the figures).
#   scripts/cluster/scaling.sh VGROOVE_MPI SUITE REPS [validate options...]
# 1. mpirun -n 1 and -n 2 (one thread per rank), REPS times each, interleaved: median wall times and
#    the speed-up.
# 2. The suite split into one shard per work unit (--shard I/N, N = the number of cases), run one
#    after the other with one thread, against one process with one thread: the overhead per shard
#    (process start, suite parse, partial report), then the merge's wall time.
# Every report is checked against the one-process report (tests/cluster/same_report.py).
set -euo pipefail
bin=$1 suite=$2 reps=$3
shift 3
src=$(cd "$(dirname "$0")/../.." && pwd)
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
now() { date +%s.%N; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
"$bin" validate "$suite" "$@" --threads 1 --out "$t/one.json" >/dev/null || [[ $? == 1 ]]
: >"$t/w1"
: >"$t/w2"
for ((r = 0; r < reps; ++r)); do
  for k in 1 2; do
    t0=$(now)
    mpirun -n "$k" "$bin" validate "$suite" "$@" --threads 1 --out "$t/mpi$k.json" --force >/dev/null || [[ $? == 1 ]]
    echo "$(now) - $t0" | bc >>"$t/w$k"
    python3 "$src/tests/cluster/same_report.py" "$t/one.json" "$t/mpi$k.json"
  done
done
w1=$(median <"$t/w1")
w2=$(median <"$t/w2")
echo "mpirun -n 1: median wall $w1 s; -n 2: $w2 s; speed-up $(echo "scale=3; $w1 / $w2" | bc) ($reps interleaved runs each: $(tr '\n' ' ' <"$t/w1")| $(tr '\n' ' ' <"$t/w2"))"

n=$(python3 -c "import json, sys; print(len(json.load(open(sys.argv[1]))['cases']))" "$t/one.json")
t0=$(now)
"$bin" validate "$suite" "$@" --threads 1 --out "$t/one2.json" --force >/dev/null || [[ $? == 1 ]]
one=$(echo "$(now) - $t0" | bc)
t0=$(now)
parts=()
for ((i = 1; i <= n; ++i)); do
  "$bin" validate "$suite" "$@" --threads 1 --shard "$i/$n" --out "$t/part$i.json" >/dev/null
  parts+=("$t/part$i.json")
done
sharded=$(echo "$(now) - $t0" | bc)
t0=$(now)
"$bin" merge "${parts[@]}" --out "$t/merged.json" >/dev/null || [[ $? == 1 ]]
merge=$(echo "$(now) - $t0" | bc)
python3 "$src/tests/cluster/same_report.py" "$t/one.json" "$t/merged.json"
echo "one process: $one s; $n shards one after the other: $sharded s (overhead $(echo "scale=4; ($sharded - $one) / $n" | bc) s per shard); merge of $n parts: $merge s"
