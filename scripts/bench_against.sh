#!/usr/bin/env bash
# Google Benchmark of this build beside another revision's, alternated in one run.
#
# Builds REV's vgroove_bench (Release, benchmarks only, in a detached worktree under the build
# directory), then runs this build's and REV's binaries on the same filter ROUNDS times each,
# alternating (this, REV, this, REV, ...), one core, and prints per benchmark the median CPU time
# of each and the ratio this / REV. The host's load moves both alike; the ratio is the figure.
#
# Default REV: the commit before the dielectric tracer (4aad92d, issue #32), for "a conductor
# scene pays nothing for the dielectric code"; default filter: the conductor tracers whose files
# the dielectric work touched (procedural surfaces, polylines, the groove and beam tracers, the
# Fresnel observers).
#
# Usage: scripts/bench_against.sh [--rev REV] [--rounds N] [--filter REGEX] [--build DIR]
#        [--min-time SECONDS]
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
rev="4aad92d^"
rounds=5
filter='BM_microsurface_(3d|flatland)/|BM_polyline_(tracer|random)|BM_groove_tracer|BM_trace_groove|BM_trace_beam|BM_effects/'
build="$here/build"
min_time=0.2

while [ $# -gt 0 ]; do
  case "$1" in
    --rev) rev="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --filter) filter="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    --min-time) min_time="$2"; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench_against.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case "$rounds" in ''|*[!0-9]*) echo "bench_against.sh: --rounds = '$rounds' must be an integer in [1, 100]" >&2; exit 2 ;; esac
if [ "$rounds" -lt 1 ] || [ "$rounds" -gt 100 ]; then
  echo "bench_against.sh: --rounds = $rounds is out of range [1, 100]" >&2; exit 2
fi

ours="$build/vgroove_bench"
[ -x "$ours" ] || { echo "bench_against.sh: $ours not found: build it first (ninja -C $build vgroove_bench)" >&2; exit 2; }
sha=$(git -C "$here" rev-parse --verify --quiet "$rev^{commit}") ||
  { echo "bench_against.sh: --rev = '$rev' is not a commit of $here" >&2; exit 2; }
short=${sha:0:7}
dir="$build/bench-against-$short"
if [ ! -x "$dir/build/vgroove_bench" ]; then
  echo "building $short's vgroove_bench in $dir ..." >&2
  [ -d "$dir/src" ] || git -C "$here" worktree add -f --detach "$dir/src" "$sha" >/dev/null
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S "$dir/src" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVGROOVE_BUILD_TESTS=OFF \
    -DVGROOVE_PYTHON=OFF -DVGROOVE_BUILD_APP=OFF -DVGROOVE_BUILD_BENCH=ON "${launcher[@]}" >/dev/null
  ninja -C "$dir/build" vgroove_bench >&2
fi
theirs="$dir/build/vgroove_bench"

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for r in $(seq 1 "$rounds"); do
  for side in ours theirs; do
    bin=$ours
    [ "$side" = theirs ] && bin=$theirs
    taskset -c 0 "$bin" --benchmark_filter="$filter" --benchmark_min_time="$min_time" \
      --benchmark_format=json > "$out/$side-$r.json"
    echo "round $r/$rounds: $side done" >&2
  done
done

python3 - "$out" "$rounds" "$(git -C "$here" rev-parse --short HEAD)" "$short" <<'EOF'
import json, statistics, sys
out, rounds, head, old = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
times, units = {"ours": {}, "theirs": {}}, {}
for side in times:
    for r in range(1, rounds + 1):
        for b in json.load(open(f"{out}/{side}-{r}.json"))["benchmarks"]:
            times[side].setdefault(b["name"], []).append(b["cpu_time"])
            units[b["name"]] = b["time_unit"]
names = [n for n in times["ours"] if n in times["theirs"]]
print(f"| benchmark | {head} (median of {rounds}, cpu) | {old} | {head} / {old} |")
print("|---|---|---|---|")
for n in names:
    a, b = statistics.median(times["ours"][n]), statistics.median(times["theirs"][n])
    print(f"| {n} | {a:.4g} {units[n]} | {b:.4g} {units[n]} | {a / b:.3f} |")
only = sorted(set(times["ours"]) ^ set(times["theirs"]))
if only:
    print(f"(in one binary only: {', '.join(only)})")
EOF
