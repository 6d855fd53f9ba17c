#!/usr/bin/env bash
# MPI runs against one process: mpi_test.sh VGROOVE_MPI MPIEXEC SOURCE_DIR CHECK
#   validate: `mpirun -n K vgroove validate` for K = 1, 2, 3 (oversubscribed on this machine) writes
#     the report of one process, value for value (timings aside): brdf and single-groove suites on
#     1, 2 and 3 ranks, table2 on 3, furnace on 2 and 3.
#   commands: the same for bench accuracy, simulate (one case: ray chunks), energy and its glass tables
#     (--eta) on 2 and 3 ranks.
#   failure: a rank that fails (VGROOVE_TEST_FAIL_RANK) ends the run with an error naming it, a
#     non-zero exit and no report.
set -euo pipefail
bin=$1 mpiexec=$2 src=$3 check=$4
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
same() { python3 "$src/tests/cluster/same_report.py" "$1" "$2"; }
fail() { echo "FAIL: $*" >&2; exit 1; }
# Open MPI refuses root unless told; --oversubscribe lets 3 ranks share 2 cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mpirun() { "$mpiexec" -n "$1" "${@:2}"; }

cat >"$t/brdf.json" <<'J'
{"name": "tiny_brdf", "kind": "brdf", "description": "a small Fig. 11 suite",
 "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [0, 40], "dimensions": ["flatland", "3d"],
 "rays": 3000, "grooves": 1000, "seed": 3, "flatland_bins": 30, "theta_bins": 9, "phi_bins": 8, "max_k": 8,
 "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}}}
J
cat >"$t/table2.json" <<'J'
{"name": "tiny_table2", "kind": "table2", "ndf": ["ggx"], "alpha": [0.5, 1.0], "percentiles": [90, 99],
 "rays": 3000, "grooves": 2000, "seed": 1,
 "paper": {"source": "made up for the tests", "max_bounces": [[2, 3], [3, 16]]}}
J
cat >"$t/table1.json" <<'J'
{"name": "tiny_table1", "kind": "table1", "description": "a small Table 1 suite",
 "groove": {"type": "symmetric", "theta_v_deg": {"from": 10, "to": 170, "step": 40}},
 "theta_i_deg": {"from": -80, "to": 80, "step": 20}, "rays": 300, "sampling": "random", "seed": 7,
 "thresholds": {"max_l1": 0.5, "mean_l1": 0.5, "max_theta_o_error_rad": 1e-9}}
J
cat >"$t/scene.json" <<'J'
{"scene": "tiny_microsurface", "geometry": {"kind": "microsurface", "ndf": "ggx", "alpha": 0.5, "grooves": 2000, "seed": 1},
 "light": {"theta_i_deg": [30], "rays": 20000, "sampling": "random", "seed": 1},
 "effects": {"fresnel": {"kind": "schlick", "channels": [{"name": "r", "F0": 0.95}]},
             "record": {"theta_o_histograms": {"bins": 30, "max_k": 4}, "energy_per_k": true}, "max_bounces": 1000}}
J
cat >"$t/furnace.json" <<'J'
{"name": "tiny_furnace", "kind": "furnace", "description": "a small furnace suite",
 "ndf": ["ggx"], "alpha": [0.3], "theta_i_deg": [0], "dimensions": ["flatland"], "max_k": 16,
 "samples": 1000, "strategy": "vndf", "rays": 1000, "grooves": 1000, "seed": 1,
 "thresholds": {"sigmas": 5, "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-6}}}
J

# ranks NAME "K..." CMD...: CMD in one process (no launcher), then under mpirun -n K for each K:
# same reports, same exit codes.
ranks() {
  local name=$1 counts=$2 rc_one=0
  shift 2
  "$bin" "$@" --threads 1 --out "$t/$name.one.json" >/dev/null || rc_one=$?
  for k in $counts; do
    local rc=0
    mpirun "$k" "$bin" "$@" --threads 1 --out "$t/$name.$k.json" >"$t/$name.$k.txt" 2>&1 || rc=$?
    [[ $rc == "$rc_one" ]] || fail "$name: exit $rc_one in one process, $rc on $k ranks: $(tail -3 "$t/$name.$k.txt")"
    same "$t/$name.one.json" "$t/$name.$k.json" || fail "$name: the report of $k ranks differs"
  done
  echo "ok: $name on $counts ranks (exit $rc_one)"
}

case $check in
  validate)
    ranks brdf "1 2 3" validate "$t/brdf.json"
    ranks table1 "1 2 3" validate "$t/table1.json"
    ranks table2 "3" validate "$t/table2.json"
    ranks furnace "2 3" validate "$t/furnace.json"
    ;;
  commands)
    ranks accuracy "2 3" bench accuracy "$t/table1.json" --rays 50,200
    ranks simulate "2 3" simulate "$t/scene.json"
    ranks energy "2 3" energy --ndf ggx,phong --dim flatland --mu-points 2 --alpha-points 2 --rays 2000 --max-k 4
    ranks glass "2 3" energy --eta 1.5 --dim 3d,flatland --alpha 0.3 --mu 1,0.5 --rays 2000 --grooves 300
    ;;
  failure)
    rc=0
    VGROOVE_TEST_FAIL_RANK=1 mpirun 2 "$bin" validate "$t/table2.json" --threads 1 --out "$t/f.json" \
      >"$t/f.txt" 2>&1 || rc=$?
    [[ $rc != 0 ]] || fail "a failed rank: exit 0"
    grep -q "rank 1 of 2" "$t/f.txt" || fail "the error does not name rank 1: $(cat "$t/f.txt")"
    [[ ! -e $t/f.json ]] || fail "a failed rank: a report was written"
    echo "ok: failed rank: exit $rc, $(grep "rank 1 of 2" "$t/f.txt" | head -1)"
    ;;
  *) fail "unknown check $check" ;;
esac
