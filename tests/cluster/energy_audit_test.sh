#!/usr/bin/env bash
# The energy audit (suite kind energy_audit) split: energy_audit_test.sh VGROOVE SOURCE_DIR [VGROOVE_MPI MPIEXEC]
#   shards: `vgroove validate SUITE --shard i/N` for N = 3 and N = 9 (cells split into their walk
#     chunks), merged in reverse order, give the report of one process value for value (timings
#     aside, same_report.py) and the same exit code;
#   mpi (when an MPI binary is given): `mpirun -n 2 vgroove validate SUITE` gives it too;
#   energy --audit: the command line's audit of the same grid is the suite's report.
set -euo pipefail
bin=$1 src=$2 mpibin=${3:-} mpiexec=${4:-}
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
same() { python3 "$src/tests/cluster/same_report.py" "$1" "$2"; }
fail() { echo "FAIL: $*" >&2; exit 1; }

cat >"$t/audit.json" <<'J'
{"name": "tiny_energy_audit", "kind": "energy_audit", "ndf": ["ggx", "beckmann"], "alpha": [0.3, 1.0],
 "mu": [0.2, 0.9], "walk_paths": 20000, "seed": 5, "max_k": 4, "grey_F0": [0.5], "metals": ["Au", "Cu"],
 "metalness": [0.5], "regions": {"rough_alpha": 0.5, "grazing_mu": 0.25},
 "thresholds": {"sigmas": 5, "vgroove_furnace": 1e-7}}
J
rc_one=0
"$bin" validate "$t/audit.json" --threads 2 --out "$t/one.json" >/dev/null || rc_one=$?
for n in 3 9; do
  parts=()
  for ((i = 1; i <= n; i++)); do
    "$bin" validate "$t/audit.json" --threads 1 --shard "$i/$n" --out "$t/part${n}_$i.json" >/dev/null ||
      fail "shard $i/$n"
    parts=("$t/part${n}_$i.json" "${parts[@]}")
  done
  rc=0
  "$bin" merge "${parts[@]}" --out "$t/merged$n.json" >/dev/null || rc=$?
  [[ $rc == "$rc_one" ]] || fail "exit $rc_one in one process, $rc merged from $n shards"
  same "$t/one.json" "$t/merged$n.json" || fail "merged report of $n shards differs"
  echo "ok: $n shards (exit $rc_one)"
done
if [[ -n $mpibin && -n $mpiexec ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  rc=0
  "$mpiexec" -n 2 "$mpibin" validate "$t/audit.json" --threads 1 --out "$t/mpi.json" >/dev/null || rc=$?
  [[ $rc == "$rc_one" ]] || fail "exit $rc_one in one process, $rc under mpirun"
  same "$t/one.json" "$t/mpi.json" || fail "the mpirun report differs"
  echo "ok: mpirun -n 2"
fi
