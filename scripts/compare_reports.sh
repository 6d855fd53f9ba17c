#!/usr/bin/env bash
# compare_reports.sh OLD_VGROOVE NEW_VGROOVE [--quick] [SUITE...]
# Runs every suite of data/suites/ (or the ones given) with both binaries and compares the reports
# value for value, timings, threads and provenance aside (tests/cluster/same_report.py), and the
# exit codes (the verdicts). --quick overrides the rays of the kinds that trace rays (--rays 2000),
# so the whole set runs in minutes; without it every suite runs as the file says. Prints one line
# per suite and exits 1 when any differs.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
old=$1 new=$2
shift 2
quick=()
if [[ ${1:-} == --quick ]]; then quick=(--rays 2000); shift; fi
suites=("$@")
[[ ${#suites[@]} -gt 0 ]] || suites=("$src"/data/suites/*.json)
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
differ=0
for s in "${suites[@]}"; do
  name=$(basename "$s" .json)
  kind=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get("kind", ""))' "$s")
  args=()
  [[ $kind == furnace || $kind == sampling ]] || args=("${quick[@]}")
  rc_old=0 rc_new=0
  s0=$SECONDS
  "$old" validate "$s" "${args[@]}" --out "$t/$name.old.json" >"$t/$name.old.txt" 2>&1 || rc_old=$?
  s1=$SECONDS
  "$new" validate "$s" "${args[@]}" --out "$t/$name.new.json" >"$t/$name.new.txt" 2>&1 || rc_new=$?
  s2=$SECONDS
  verdict="same"
  if [[ $rc_old != "$rc_new" ]]; then
    verdict="exit $rc_old (old) against $rc_new (new)"
  elif [[ ! -f $t/$name.old.json || ! -f $t/$name.new.json ]]; then
    verdict="no report (exit $rc_old): $(tail -1 "$t/$name.new.txt")"
  elif ! d=$(python3 "$src/tests/cluster/same_report.py" --provenance-aside "$t/$name.old.json" "$t/$name.new.json" | sed "s|$t/||g"); then
    verdict="$d"
  fi
  [[ $verdict == same ]] || differ=1
  printf '%-36s %-18s exit %s  old %4ss new %4ss  %s\n' "$name" "${kind:-single-groove}" "$rc_new" $((s1 - s0)) \
    $((s2 - s1)) "$verdict"
done
exit $differ
