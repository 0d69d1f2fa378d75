#!/usr/bin/env bash
# tools/sweep/parallel.sh PLAN N [--runs DIR] [--result DIR] [GNU parallel options...]
#
# Runs the N shards of a sweep plan (sandbox sweep plan ...) with GNU parallel, N at once, then merges them:
#   tools/sweep/parallel.sh plan.jsonl 2                       # this machine, 2 shards at once
#   tools/sweep/parallel.sh plan.jsonl 8 --sshlogin 4/node1,4/node2   # 4 shards on each of two machines
# The run folder (default PLAN without .jsonl, plus .runs) and the result folder (default ... .result) are
# given to the shards as absolute paths: with --sshlogin, the repository, the binary and these folders must be
# at the same paths on every machine (a shared file system), and each machine must have the same build.
# Run again after an interruption: the shards skip the cases already done. Any other option is passed to
# parallel before the command (e.g. --sshloginfile FILE, --retries 2). SANDBOX overrides the binary
# (default build/bin/sandbox of this repository). Exit: that of the merge, or 1 when a shard failed.
set -uo pipefail
source "$(dirname "$0")/plan_args.sh"
read_plan_args "GNU parallel options" "$@"
parallel_options=("${passed_options[@]}")
repo=$(cd "$(dirname "$0")/../.." && pwd)
sandbox=$(realpath "${SANDBOX:-$repo/build/bin/sandbox}")
command -v parallel > /dev/null || { echo "$0: GNU parallel is not installed (tools/setup.sh)" >&2; exit 2; }
[[ -x $sandbox ]] || { echo "$0: $sandbox: not built (make build)" >&2; exit 2; }

# One job per shard; --tag prefixes each line with its shard, --halt never lets the others finish.
parallel --will-cite --jobs "$shards" --halt never --tag --line-buffer "${parallel_options[@]}" \
  "$sandbox" sweep run "$plan" --shard {}/"$shards" --out "$runs" ::: $(seq 1 "$shards")
failed_shards=$?
"$sandbox" sweep merge "$runs" --out "$result"
merged=$?
if [[ $failed_shards -ne 0 ]]; then
  echo "$0: $failed_shards shard(s) failed; see above, run again to resume" >&2
  exit 1
fi
exit $merged
