#!/usr/bin/env bash
# tools/sweep/submit.sh PLAN N [--runs DIR] [--result DIR] [sbatch options...]
#
# Submits a sweep plan to Slurm: a job array of N shards (tools/sweep/slurm.sbatch), and the merge as a job
# that starts once every shard has ended (--dependency=afterany: the merge then refuses missing cases and
# names failed ones, so a broken shard is reported rather than silently waited on). Prints both job ids;
# the last line is the merge's. The run folder (default PLAN without .jsonl, plus .runs) and the result
# folder (... .result) must be on a file system the nodes share; the shards' and the merge's logs go to the
# run folder. Other options go to both sbatch calls (e.g. --partition=long, --time=2:00:00). SANDBOX
# overrides the binary (default build/bin/sandbox of this repository, by absolute path).
#   tools/sweep/submit.sh plan.jsonl 40 --partition=short
set -euo pipefail
source "$(dirname "$0")/plan_args.sh"
read_plan_args "sbatch options" "$@"
sbatch_options=("${passed_options[@]}")
here=$(cd "$(dirname "$0")" && pwd)
sandbox=$(realpath "${SANDBOX:-$here/../../build/bin/sandbox}")
[[ -x $sandbox ]] || { echo "$0: $sandbox: not built (make build)" >&2; exit 2; }
command -v sbatch > /dev/null || { echo "$0: sbatch not found (no Slurm here)" >&2; exit 2; }
mkdir -p "$runs"

array=$(sbatch --parsable --array=1-"$shards" --output="$runs/slurm-%A_%a.out" "${sbatch_options[@]}" \
  "$here/slurm.sbatch" "$plan" "$shards" "$runs" "$sandbox")
array=${array%%;*}
printf -v merge_command '%q sweep merge %q --out %q' "$sandbox" "$runs" "$result"
merge=$(sbatch --parsable --job-name=deform-sweep-merge --dependency=afterany:"$array" \
  --output="$runs/slurm-merge-%j.out" "${sbatch_options[@]}" --wrap="$merge_command")
merge=${merge%%;*}
echo "shards: job array $array (1-$shards), results in $runs/cases"
echo "merge: job $merge after the array, into $result (log $runs/slurm-merge-$merge.out)"
