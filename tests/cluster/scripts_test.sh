#!/usr/bin/env bash
# scripts/cluster/ on this machine: scripts_test.sh VGROOVE SOURCE_DIR
#   parallel_shards.sh (GNU parallel; skipped, exit 77, when absent) and slurm_shards.sh with a
#   stand-in sbatch that runs the array's tasks one by one and then the dependent merge job: both
#   write the report of one process (timings aside). A failing task leaves no report.
set -euo pipefail
bin=$1 src=$2
t=$(mktemp -d)
trap 'rc=$?; ((rc == 0 || rc == 77)) || cat "$t"/state*/log 2>/dev/null | tail -5 >&2; rm -rf "$t"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cat >"$t/table1.json" <<'J'
{"name": "tiny_table1", "kind": "table1", "description": "a small Table 1 suite",
 "groove": {"type": "symmetric", "theta_v_deg": {"from": 10, "to": 170, "step": 40}},
 "theta_i_deg": {"from": -80, "to": 80, "step": 20}, "rays": 300, "sampling": "random", "seed": 7,
 "thresholds": {"max_l1": 0.5, "mean_l1": 0.5, "max_theta_o_error_rad": 1e-9}}
J
"$bin" validate "$t/table1.json" --threads 2 --out "$t/one.json" >/dev/null

# A stand-in for sbatch: --array=1-N runs the --wrap command once per task (SLURM_ARRAY_TASK_ID),
# a job with --dependency=afterok:ID runs only if every task of ID succeeded.
mkdir "$t/bin"
cat >"$t/bin/sbatch" <<'S'
#!/usr/bin/env bash
set -u
state=${FAKE_SLURM_STATE:?}
array="" wrap="" dep=""
while (($#)); do
  case $1 in
    --array=*) array=${1#--array=} ;;
    --dependency=afterok:*) dep=${1#--dependency=afterok:} ;;
    --wrap) wrap=$2; shift ;;
  esac
  shift
done
id=$(( $(cat "$state/next" 2>/dev/null || echo 100) + 1 ))
echo "$id" >"$state/next"
if [[ -n $dep && -e $state/failed-$dep ]]; then echo "$id"; exit 0; fi
if [[ -n $array ]]; then
  for ((i = ${array%-*}; i <= ${array#*-}; ++i)); do
    SLURM_ARRAY_TASK_ID=$i SLURM_CPUS_PER_TASK=1 bash -c "$wrap" >>"$state/log" 2>&1 || touch "$state/failed-$id"
  done
else
  bash -c "$wrap" >>"$state/log" 2>&1 || touch "$state/failed-$id"
fi
echo "$id"
S
chmod +x "$t/bin/sbatch"
mkdir "$t/state"
FAKE_SLURM_STATE=$t/state SBATCH=$t/bin/sbatch \
  bash "$src/scripts/cluster/slurm_shards.sh" 3 "$t/slurm.json" --time=00:10:00 -- "$bin" validate "$t/table1.json"
python3 "$src/tests/cluster/same_report.py" "$t/one.json" "$t/slurm.json" || fail "slurm_shards.sh: report differs"
[[ $(ls "$t/slurm.parts"/part-*.json | wc -l) == 3 ]] || fail "slurm_shards.sh: not 3 parts"
echo "ok: slurm_shards.sh (3 array tasks, then the merge job)"
# A task that fails (an option the command refuses): no merge, no report.
mkdir "$t/state2"
FAKE_SLURM_STATE=$t/state2 SBATCH=$t/bin/sbatch \
  bash "$src/scripts/cluster/slurm_shards.sh" 2 "$t/bad.json" -- "$bin" validate "$t/table1.json" --rays 0
[[ ! -e $t/bad.json ]] || fail "slurm_shards.sh: failed tasks, yet a report"
echo "ok: slurm_shards.sh: failed tasks, no report"

if ! command -v parallel >/dev/null; then
  [[ ${VGROOVE_NO_SKIP:-} != 1 ]] || fail "GNU parallel is not installed (VGROOVE_NO_SKIP=1 forbids skipping)"
  echo "skipped: GNU parallel is not installed (apt-get install parallel; scripts/install-deps.sh installs it)"
  exit 77
fi
bash "$src/scripts/cluster/parallel_shards.sh" 4 2 1 "$t/parallel.json" -- "$bin" validate "$t/table1.json" >/dev/null
python3 "$src/tests/cluster/same_report.py" "$t/one.json" "$t/parallel.json" || fail "parallel_shards.sh: report differs"
echo "ok: parallel_shards.sh (4 shards, 2 at a time)"
rc=0
bash "$src/scripts/cluster/parallel_shards.sh" 2 2 1 "$t/bad.json" -- "$bin" validate "$t/table1.json" --rays 0 \
  >/dev/null 2>&1 || rc=$?
[[ $rc != 0 && ! -e $t/bad.json ]] || fail "parallel_shards.sh: a failed shard, yet exit $rc or a report"
echo "ok: parallel_shards.sh: a failed shard, exit $rc, no report"
