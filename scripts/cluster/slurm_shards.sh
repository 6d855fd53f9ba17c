#!/usr/bin/env bash
# One vgroove run split over a Slurm job array: array task I of N runs `COMMAND --shard I/N` and
# writes PARTS/part-I.json; a merge job, started when every task has succeeded (afterok), joins the
# parts into REPORT. A task that fails leaves its part missing and is recorded FAILED with its exit
# code (its messages in PARTS/slurm-ARRAY_I.out); the merge job never starts (submitted with
# --kill-on-invalid-dep=yes, Slurm cancels it: CANCELLED, Reason=DependencyNeverSatisfied), and no
# report is written. `scontrol show job ARRAY` (or sacct) lists the tasks' states. Resubmit the
# failed tasks with --array=I,... and the same PARTS, then the merge by hand (`vgroove merge
# PARTS/*.json`).
#
#   scripts/cluster/slurm_shards.sh N REPORT [sbatch options...] -- COMMAND...
#   scripts/cluster/slurm_shards.sh 64 fig11.json --time=02:00:00 --cpus-per-task=32 -- \
#       build/vgroove validate data/suites/fig11.json --rays 1000000000
#
# Each task runs with --threads $SLURM_CPUS_PER_TASK (all its cores otherwise). COMMAND is any of
# `vgroove validate`, `vgroove bench accuracy`, `vgroove simulate`, `vgroove energy`, without
# --out and --shard. SBATCH (default sbatch) names the submitting command.
set -euo pipefail
if (($# < 4)); then
  sed -n '2,17p' "$0" >&2
  exit 2
fi
n=$1 report=$2
shift 2
[[ $n =~ ^[1-9][0-9]*$ ]] || { echo "slurm_shards: N must be a positive integer, got '$n'" >&2; exit 2; }
opts=()
while (($#)) && [[ $1 != -- ]]; do opts+=("$1"); shift; done
(($#)) || { echo "slurm_shards: no '--' before the command" >&2; exit 2; }
shift
(($#)) || { echo "slurm_shards: no command after '--'" >&2; exit 2; }
sbatch=${SBATCH:-sbatch}
vgroove=$1
parts=${report%.json}.parts
mkdir -p "$parts"
[[ ! -e $report ]] || { echo "slurm_shards: $report exists; move it away first" >&2; exit 2; }

q() { printf '%q ' "$@"; }
q1() { printf '%q' "$1"; }
task="threads=\${SLURM_CPUS_PER_TASK:-0}; exec $(q "$@") --threads \$threads --shard \${SLURM_ARRAY_TASK_ID}/$n --out $(q1 "$parts")/part-\${SLURM_ARRAY_TASK_ID}.json --force"
array=$("$sbatch" --parsable --job-name=vgroove-shards --array=1-"$n" --output="$parts/slurm-%A_%a.out" \
  "${opts[@]}" --wrap "$task")
array=${array%%;*}
merge="exec $(q1 "$vgroove") merge $(q1 "$parts")/part-*.json --out $(q1 "$report")"
merge_id=$("$sbatch" --parsable --job-name=vgroove-merge --dependency=afterok:"$array" --kill-on-invalid-dep=yes \
  --output="$parts/slurm-merge-%j.out" --wrap "$merge")
echo "submitted: array job $array ($n shards into $parts/), merge job ${merge_id%%;*} (into $report)"
