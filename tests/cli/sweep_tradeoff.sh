#!/usr/bin/env bash
# sweep_tradeoff.sh SANDBOX WORK [MODE]: `sandbox tradeoff --quick` on a short wall crash in one process,
# and the same sweep planned, run in 3 shards (two at once) and merged, give the same tradeoff.csv in every
# column but the timings (and the Pareto flag, which is decided by them). MODE shards (the default) runs the
# shards itself; parallel runs them through tools/sweep/parallel.sh (skipped, exit 77, when GNU parallel is
# missing); one only makes the one-process result, in WORK/one, for the other modes' tests (a test of its
# own, so that `ctest -j` runs it beside others). ONE_PROCESS_DIR, when set, is the one-process result made
# by another test (the same options).
set -uo pipefail
sandbox=$1
work=$2
mode=${3:-shards}
here=$(cd "$(dirname "$0")" && pwd)
source "$here/sweep_support.sh"
if [[ $mode == parallel ]] && ! command -v parallel > /dev/null; then
  echo "SKIPPED: GNU parallel is not installed (tools/setup.sh installs it)"
  exit 77
fi
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

options=(--quick --scene wall_crash --set duration_s=0.3)
if [[ $mode == one ]]; then
  "$sandbox" tradeoff "${options[@]}" --out one > one.log 2>&1 || fail "one-process tradeoff: $(tail -3 one.log)"
  [[ $(wc -l < one/tradeoff.csv) -eq 17 ]] || fail "one/tradeoff.csv: expected 16 rows"
  echo "sweep tradeoff (one): the one-process table, 16 rows"
  exit 0
fi
if [[ -n ${ONE_PROCESS_DIR:-} ]]; then  # the one-process result another test made
  ln -s "$ONE_PROCESS_DIR" one
else
  "$sandbox" tradeoff "${options[@]}" --out one > one.log 2>&1 || fail "one-process tradeoff: $(tail -3 one.log)"
fi
"$sandbox" sweep plan tradeoff "${options[@]}" --out plan.jsonl > /dev/null || fail "plan"
[[ $(wc -l < plan.jsonl) -eq 17 ]] || fail "plan.jsonl: expected a header and 16 cases"
if [[ $mode == parallel ]]; then
  SANDBOX=$sandbox bash "$here/../../tools/sweep/parallel.sh" plan.jsonl 3 --runs runs --result merged > parallel.log 2>&1 ||
    fail "parallel.sh: $(tail -5 parallel.log)"
else
  "$sandbox" sweep run plan.jsonl --shard 1/3 --out runs > shard1.log 2>&1 &
  first=$!
  "$sandbox" sweep run plan.jsonl --shard 2/3 --out runs > shard2.log 2>&1 || fail "shard 2/3"
  wait "$first" || fail "shard 1/3"
  out=$("$sandbox" sweep merge runs --out merged 2>&1)
  [[ $? -eq 2 && $out == *"case(s) missing: 0002, 0005, 0008, 0011, 0014"* ]] ||
    fail "a merge without shard 3/3 should name its cases: $out"
  "$sandbox" sweep run plan.jsonl --shard 3/3 --out runs > shard3.log 2>&1 || fail "shard 3/3"
  "$sandbox" sweep merge runs --out merged > merge.log 2>&1 || fail "merge: $(tail -3 merge.log)"
fi
same_measures one/tradeoff.csv merged/tradeoff.csv
[[ $(wc -l < merged/tradeoff.csv) -eq 17 ]] || fail "merged/tradeoff.csv: expected 16 rows"
# The errors are measured, not zero everywhere: the reference alone has none.
[[ $(awk -F, 'NR > 1 && $9 == 0' merged/tradeoff.csv | wc -l) -eq 1 ]] || fail "expected one row without error"
[[ -s merged/tradeoff.md && -s merged/tradeoff_wall_crash.dat ]] || fail "the merge lacks the Markdown or plot data"
echo "sweep tradeoff ($mode): the merged table equals the one-process one outside the timings"
