#!/usr/bin/env bash
# sweep_kind.sh SANDBOX WORK KIND TABLE [OPTIONS...]: `sandbox KIND OPTIONS` in one process (`bench grid`
# for KIND grid), and `sandbox sweep plan KIND OPTIONS` run in 2 shards at once and merged, write the same
# TABLE (a CSV) in every column but the timings. ONE_PROCESS_DIR, when set, is a folder that command already
# wrote (by another test), used instead of running it again.
set -uo pipefail
sandbox=$1
work=$2
kind=$3
table=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
source "$here/sweep_support.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

command=("$kind")
[[ $kind == grid ]] && command=(bench grid)
if [[ -n ${ONE_PROCESS_DIR:-} ]]; then
  ln -s "$ONE_PROCESS_DIR" one
else
  "$sandbox" "${command[@]}" "$@" --out one > one.log 2>&1 || fail "sandbox ${command[*]} $*: $(tail -3 one.log)"
fi
"$sandbox" sweep plan "$kind" "$@" --out plan.jsonl > /dev/null || fail "sweep plan $kind"
cases=$(($(wc -l < plan.jsonl) - 1))
[[ $cases -ge 2 ]] || fail "plan.jsonl: $cases cases, expected at least 2 to shard"
# The two shards at once, as a cluster runs them (each writes only its own cases).
"$sandbox" sweep run plan.jsonl --shard 1/2 --out runs > shard1.log 2>&1 &
first=$!
"$sandbox" sweep run plan.jsonl --shard 2/2 --out runs > shard2.log 2>&1 || fail "shard 2/2"
wait "$first" || fail "shard 1/2"
"$sandbox" sweep merge runs --out merged > merge.log 2>&1 || fail "merge: $(tail -3 merge.log)"
same_measures "one/$table" "merged/$table"
echo "sweep $kind: $cases cases in 2 shards, merged $table equals the one-process one outside the timings"
