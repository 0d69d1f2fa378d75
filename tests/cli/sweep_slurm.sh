#!/usr/bin/env bash
# sweep_slurm.sh SANDBOX WORK: the `cluster` test. Starts a one-node Slurm (tools/sweep/local-slurm.sh),
# submits a small trade-off plan as a 4-task job array with the dependent merge (tools/sweep/submit.sh),
# waits for the merge, and checks that the merged tradeoff.csv equals `sandbox tradeoff`'s in every column
# but the timings. Exits 77 (CTest: skipped, with the reason) when Slurm cannot be started here.
set -uo pipefail
sandbox=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
tools=$here/../../tools/sweep
source "$here/sweep_support.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

state=$work/slurm
# Ports from the folder's path, so two checkouts testing on one machine do not collide.
port=$((20000 + 2 * ($(cksum <<< "$work" | cut -d' ' -f1) % 10000)))
if ! SLURMCTLD_PORT=${SLURMCTLD_PORT:-$port} SLURMD_PORT=${SLURMD_PORT:-$((port + 1))} \
  bash "$tools/local-slurm.sh" start "$state" > slurm_start.log 2>&1; then
  echo "SKIPPED: a local Slurm could not be started here: $(tail -2 slurm_start.log | tr '\n' ' ')"
  exit 77
fi
trap 'bash "$tools/local-slurm.sh" stop "$state" > /dev/null 2>&1' EXIT
export SLURM_CONF=$state/slurm.conf

options=(--quick --scene wall_crash --set duration_s=0.3)
"$sandbox" sweep plan tradeoff "${options[@]}" --out plan.jsonl > /dev/null || fail "plan"
SANDBOX=$sandbox bash "$tools/submit.sh" plan.jsonl 4 --runs "$work/runs" --result "$work/merged" > submit.log 2>&1 ||
  fail "submit.sh: $(cat submit.log)"
array=$(sed -n 's/^shards: job array \([0-9]*\) .*/\1/p' submit.log)
merge=$(sed -n 's/^merge: job \([0-9]*\) .*/\1/p' submit.log)
[[ -n $array && -n $merge ]] || fail "no job ids in: $(cat submit.log)"
if [[ -n ${ONE_PROCESS_DIR:-} ]]; then  # the one-process result another test made (the same options)
  ln -s "$ONE_PROCESS_DIR" one
else
  "$sandbox" tradeoff "${options[@]}" --out one > one.log 2>&1 || fail "one-process tradeoff"
fi

state_of() { scontrol show job "$1" 2> /dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | sort -u | tr '\n' ' '; }
for _ in $(seq 1 600); do
  merge_state=$(state_of "$merge")
  [[ $merge_state == *COMPLETED* || $merge_state == *FAILED* || $merge_state == *CANCELLED* ]] && break
  sleep 0.5
done
[[ $merge_state == "COMPLETED " ]] || fail "merge job $merge: '$merge_state'; $(cat runs/slurm-merge-*.out 2> /dev/null | tail -5)"
tasks=$(ls runs/slurm-"$array"_*.out 2> /dev/null | wc -l)
[[ $tasks -eq 4 ]] || fail "expected 4 array task logs, found $tasks"
for i in 1 2 3 4; do
  grep -q "shard $i/4 of .*: 4 cases, 4 run, 0 already done, 0 failed" runs/slurm-"${array}_$i".out ||
    fail "array task $i did not run its 4 cases: $(tail -2 runs/slurm-"${array}_$i".out)"
done
same_measures one/tradeoff.csv merged/tradeoff.csv
echo "sweep on Slurm: 4 array tasks and the dependent merge; the merged table equals the one-process one"
