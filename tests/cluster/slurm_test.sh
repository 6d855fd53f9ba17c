#!/usr/bin/env bash
# scripts/cluster/ on a real Slurm: slurm_test.sh VGROOVE SOURCE_DIR [VGROOVE_MPI]
#   Starts a single-node cluster of its own in a temporary directory (Debian's munge and slurm-wlm:
#   munged, slurmctld and slurmd on localhost, free ports, a generated slurm.conf; nothing of the
#   machine's own /etc/slurm or /etc/munge is used), then:
#   - slurm_shards.sh: the array job (3 shards) and the dependent merge job write the report of one
#     process (timings aside);
#   - a failing array task (task 2 exits 3): the merge job never runs (Slurm cancels it,
#     DependencyNeverSatisfied), the task is recorded FAILED with its exit code and its message is in
#     its output file, and no report is written;
#   - slurm_mpi.sbatch (when VGROOVE_MPI, vgroove built with MPI, is given): 2 ranks started by srun
#     (PMIx) write the report of one process; with rank 1 made to fail the job fails, naming it, and
#     writes no report.
#   Stops every daemon it started (by pid) on exit. Skipped (exit 77) with the reason when the packages
#   are not installed (scripts/install-deps.sh installs them) or when not run as root (slurmd starts
#   jobs as their users); VGROOVE_NO_SKIP=1 (CI) makes a skip a failure.
set -euo pipefail
bin=$1 src=$2 mpibin=${3:-}
fail() { echo "FAIL: $*" >&2; exit 1; }
skip() {
  [[ ${VGROOVE_NO_SKIP:-} != 1 ]] || fail "$1 (VGROOVE_NO_SKIP=1 forbids skipping)"
  echo "skipped: $1"
  exit 77
}
for c in munged mungekey slurmctld slurmd sbatch scontrol squeue sinfo scancel srun; do
  command -v "$c" >/dev/null || skip "Slurm is not installed ($c missing: apt-get install munge slurmctld slurmd slurm-client)"
done
[[ $(id -u) == 0 ]] || skip "a real Slurm needs root (slurmd starts jobs as their users)"
# A Slurm job running this test must not lend its variables to the test's own cluster.
while read -r v; do unset "$v"; done < <(env | sed -n 's/^\(SLURM_[A-Z_]*\)=.*/\1/p')

t=$(mktemp -d)
chmod 755 "$t"  # munged wants its socket's directories searchable by all
pids=()
cleanup() {
  local rc=$?
  if ((${#pids[@]})); then
    # Only the test's own cluster's jobs (never a real cluster's: SLURM_CONF must be the test's).
    [[ ${SLURM_CONF:-} != "$t/slurm.conf" ]] || scancel --quiet --user="$(id -un)" 2>/dev/null || true
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
    for p in "${pids[@]}"; do
      for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$p" 2>/dev/null || true
    done
  fi
  if ((rc != 0 && rc != 77)); then
    for f in "$t"/slurmctld.log "$t"/slurmd.log "$t"/munge-key/munged.log; do
      [[ -e $f ]] && { echo "--- $f" >&2; tail -15 "$f" >&2; }
    done
  fi
  rm -rf "$t"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# munge: a key of its own, the socket in the test's directory.
mkdir -m 700 "$t/munge-key" "$t/state" "$t/spool"
mkdir -m 755 "$t/munge"
mungekey --create --keyfile="$t/munge-key/munge.key" >/dev/null 2>&1
munged --foreground --key-file="$t/munge-key/munge.key" --socket="$t/munge/socket" \
  --pid-file="$t/munge-key/munged.pid" --seed-file="$t/munge-key/seed" >"$t/munge-key/munged.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do [[ -S $t/munge/socket ]] && break; sleep 0.1; done
[[ -S $t/munge/socket ]] || fail "munged did not start"

host=$(hostname -s)
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s:
    x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
export SLURM_CONF=$t/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=vgroove-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$t/munge/socket
CredType=cred/munge
StateSaveLocation=$t/state
SlurmdSpoolDir=$t/spool
SlurmctldPidFile=$t/slurmctld.pid
SlurmdPidFile=$t/slurmd.pid
SlurmctldLogFile=$t/slurmctld.log
SlurmdLogFile=$t/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MinJobAge=3600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=100 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -c >/dev/null 2>&1 &
pids+=($!)
slurmd -D -N "$host" >/dev/null 2>&1 &
pids+=($!)
for _ in $(seq 300); do
  [[ $(sinfo -h -o %T 2>/dev/null) == idle ]] && break
  sleep 0.2
done
[[ $(sinfo -h -o %T 2>/dev/null) == idle ]] || fail "the node did not become idle: $(sinfo 2>&1 | tail -1)"
echo "ok: slurmctld and slurmd on $host, ports $ctld_port and $slurmd_port ($SECONDS s)"
# Should this script be killed outright (SIGKILL: no cleanup, its directory left), a watchdog in a
# session of its own stops the daemons it started and removes the directory once the script is gone.
setsid bash -c 'while kill -0 "$1" 2>/dev/null; do sleep 2; done; [[ -d $2 ]] || exit 0
  kill "${@:3}" 2>/dev/null; sleep 2; rm -rf "$2"' watchdog $$ "$t" "${pids[@]}" </dev/null >/dev/null 2>&1 &

# A job's state and exit code ("COMPLETED 0:0"); its reason ("DependencyNeverSatisfied").
state() { scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\) .*/\1/p;s/.* ExitCode=\([0-9:]*\).*/\1/p' | paste -sd ' '; }
reason() { scontrol show job "$1" | sed -n 's/.* Reason=\([A-Za-z_]*\).*/\1/p' | head -1; }
# Waits until job $1 has left the queue (finished, failed or cancelled), at most 180 s.
wait_gone() {
  for _ in $(seq 900); do
    [[ -z $(squeue -h -j "$1" 2>/dev/null) ]] && return 0
    sleep 0.2
  done
  fail "job $1 still queued after 180 s: $(squeue -j "$1" | tail -1)"
}
# Job IDs from slurm_shards.sh's line "submitted: array job A (...), merge job M (...)".
ids() { sed -n 's/^submitted: array job \([0-9]*\) .*merge job \([0-9]*\) .*/\1 \2/p' "$1"; }

cat >"$t/table1.json" <<'J'
{"name": "tiny_table1", "kind": "table1", "description": "a small Table 1 suite",
 "groove": {"type": "symmetric", "theta_v_deg": {"from": 10, "to": 170, "step": 40}},
 "theta_i_deg": {"from": -80, "to": 80, "step": 20}, "rays": 300, "sampling": "random", "seed": 7,
 "thresholds": {"max_l1": 0.5, "mean_l1": 0.5, "max_theta_o_error_rad": 1e-9}}
J
"$bin" validate "$t/table1.json" --threads 2 --out "$t/one.json" >/dev/null

# The array job and its merge.
bash "$src/scripts/cluster/slurm_shards.sh" 3 "$t/slurm.json" --time=00:10:00 --cpus-per-task=1 -- \
  "$bin" validate "$t/table1.json" | tee "$t/submitted"
read -r array merge < <(ids "$t/submitted")
wait_gone "$merge"
for i in 1 2 3; do
  [[ $(state "${array}_$i") == "COMPLETED 0:0" ]] || fail "task $i: $(state "${array}_$i")"
done
[[ $(state "$merge") == "COMPLETED 0:0" ]] || fail "merge job: $(state "$merge")"
python3 "$src/tests/cluster/same_report.py" "$t/one.json" "$t/slurm.json" || fail "slurm_shards.sh: report differs"
[[ $(ls "$t/slurm.parts"/part-*.json | wc -l) == 3 ]] || fail "slurm_shards.sh: not 3 parts"
echo "ok: slurm_shards.sh: 3 array tasks and the merge job completed; the report equals one process's ($SECONDS s)"

# Task 2 of 3 fails: its exit code is recorded, the merge job is cancelled and never runs.
cat >"$t/flaky" <<EOF
#!/bin/sh
if [ "\${SLURM_ARRAY_TASK_ID:-}" = 2 ]; then echo "flaky: task 2 fails on purpose" >&2; exit 3; fi
exec $(printf %q "$bin") "\$@"
EOF
chmod +x "$t/flaky"
bash "$src/scripts/cluster/slurm_shards.sh" 3 "$t/bad.json" --time=00:10:00 --cpus-per-task=1 -- \
  "$t/flaky" validate "$t/table1.json" | tee "$t/submitted"
read -r array merge < <(ids "$t/submitted")
wait_gone "$merge"
[[ $(state "${array}_2") == "FAILED 3:0" ]] || fail "task 2: $(state "${array}_2")"
grep -q "flaky: task 2 fails on purpose" "$t/bad.parts/slurm-${array}_2.out" || fail "task 2: its message is not in its output"
for i in 1 3; do
  [[ $(state "${array}_$i") == "COMPLETED 0:0" ]] || fail "task $i: $(state "${array}_$i")"
done
[[ $(state "$merge") == "CANCELLED 0:0" && $(reason "$merge") == DependencyNeverSatisfied ]] ||
  fail "merge job: $(state "$merge"), $(reason "$merge")"
[[ ! -e $t/bad.json ]] || fail "a task failed, yet a report"
[[ -z $(ls "$t/bad.parts"/slurm-merge-* 2>/dev/null) ]] || fail "the merge job ran"
echo "ok: slurm_shards.sh: task 2 FAILED (exit 3), the merge job CANCELLED (DependencyNeverSatisfied) unrun, no report ($SECONDS s)"

# MPI under srun: vgroove built with MPI, 2 ranks on the node's cores.
if [[ -n $mpibin ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  job=$(sbatch --parsable --ntasks=2 --cpus-per-task=1 --export=ALL,SLURM_MPI_TYPE=pmix --output="$t/mpi-%j.out" \
    "$src/scripts/cluster/slurm_mpi.sbatch" "$t/mpi.json" "$mpibin" validate "$t/table1.json")
  wait_gone "$job"
  [[ $(state "$job") == "COMPLETED 0:0" ]] || { cat "$t/mpi-$job.out" >&2; fail "MPI job: $(state "$job")"; }
  python3 "$src/tests/cluster/same_report.py" "$t/one.json" "$t/mpi.json" || fail "slurm_mpi.sbatch: report differs"
  # Two ranks indeed: rank 1 made to fail (app/distributed.h's test hook) ends the job, naming it.
  job=$(sbatch --parsable --ntasks=2 --cpus-per-task=1 --export=ALL,SLURM_MPI_TYPE=pmix,VGROOVE_TEST_FAIL_RANK=1 \
    --output="$t/mpi-%j.out" "$src/scripts/cluster/slurm_mpi.sbatch" "$t/mpi-bad.json" "$mpibin" validate "$t/table1.json")
  wait_gone "$job"
  [[ $(state "$job") == FAILED* ]] || fail "MPI job with a failing rank: $(state "$job")"
  grep -q "rank 1 of 2" "$t/mpi-$job.out" || fail "MPI job: the error does not name rank 1 of 2: $(tail -3 "$t/mpi-$job.out")"
  [[ ! -e $t/mpi-bad.json ]] || fail "MPI job with a failing rank: a report was written"
  echo "ok: slurm_mpi.sbatch: 2 ranks under srun (PMIx) give the report of one process; a failing rank ($(state "$job")) is named, no report ($SECONDS s)"
fi
