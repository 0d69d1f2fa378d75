#!/usr/bin/env bash
# sweep_resume.sh SANDBOX WORK PART: PART resume: a custom sweep's shard killed halfway and run again
# completes with no case lost, none run twice and the kept results untouched; its merge equals a clean run's.
# PART refusals (after resume, in the same WORK: its plan and clean run): the merge refuses a folder with a
# missing or a foreign case, naming it; a failing case is recorded and reported; a plan of another build
# warns and --strict refuses it; a changed scene file is noticed. Two tests, so that neither takes a minute
# under the sanitizers.
set -uo pipefail
sandbox=$1
work=$2
part=$3
here=$(cd "$(dirname "$0")" && pwd)
source "$here/sweep_support.sh"
refusals() {
  # Missing and foreign cases: refused (exit 2), named, nothing written.
  cp -r clean missing && rm missing/cases/0003.json
  out=$("$sandbox" sweep merge missing --out missing_result 2>&1)
  [[ $? -eq 2 && $out == *"1 case(s) missing: 0003"* ]] || fail "missing case not refused by name: $out"
  [[ ! -e missing_result ]] || fail "a refused merge wrote missing_result"
  "$sandbox" sweep plan custom --scene wall_crash "${small[@]}" --vary vehicle.start.speed_kmh=20,30,40,50,56 \
    --out other.jsonl > /dev/null || fail "other plan"
  "$sandbox" sweep run other.jsonl --shard 5/5 --out other > /dev/null || fail "other run"
  cp -r clean foreign && cp other/cases/0004.json foreign/cases/0004.json && echo '{}' > foreign/cases/0042.json
  out=$("$sandbox" sweep merge foreign --out foreign_result 2>&1)
  [[ $? -eq 2 && $out == *"cases/0004.json (of another plan)"* && $out == *"cases/0042.json (no case of the plan)"* ]] ||
    fail "foreign cases not refused by name: $out"
  out=$("$sandbox" sweep run plan.jsonl --out other 2>&1)
  [[ $? -eq 2 && $out == *"other/plan.jsonl: this folder holds the results of another plan"* ]] ||
    fail "a run into another plan's folder not refused: $out"

  out=$("$sandbox" sweep run plan.jsonl --out /proc/no_such_folder 2>&1)
  [[ $? -eq 2 && $out == *"--out: cannot create /proc/no_such_folder/cases"* ]] || fail "a bad --out not refused: $out"

  # A case that fails (a bad value slipped into the plan): recorded with its error and exit code, the rest
  # run, the shard exits 1, and the merge names it.
  sed 's/control_points=500"/control_points=-5"/' plan.jsonl > broken.jsonl
  "$sandbox" sweep run broken.jsonl --out broken > broken.log 2>&1
  [[ $? -eq 1 ]] || fail "a shard with a failed case should exit 1"
  grep -q "6 cases, 6 run, 0 already done, 3 failed" broken.log || fail "failed cases: $(tail -2 broken.log)"
  grep -q '"status":"failed"' broken/cases/0001.json && grep -q '"exit_code":2' broken/cases/0001.json &&
    grep -q 'control_points' broken/cases/0001.json || fail "the failed result lacks status, exit code or error"
  out=$("$sandbox" sweep merge broken --out broken_result 2>&1)
  [[ $? -eq 1 && $out == *"case 0001"*"failed, exit 2"* && $out == *"3 case(s) of broken failed"* ]] ||
    fail "the merge did not report the failed cases: $out"

  # Another build: a warning, or with --strict a refusal before anything runs.
  sed '1s/"version":"[^"]*"/"version":"0.0.0+another"/' plan.jsonl > another.jsonl
  out=$("$sandbox" sweep run another.jsonl --shard 1/6 --out another 2>&1) || fail "another build: $out"
  [[ $out == *"warning: another.jsonl: made by build 0.0.0+another"* ]] || fail "no warning for another build: $out"
  out=$("$sandbox" sweep run another.jsonl --strict --out another_strict 2>&1)
  [[ $? -eq 2 && $out == *"made by build 0.0.0+another"*"--strict"* && ! -e another_strict ]] ||
    fail "--strict did not refuse another build: $out"

  # A scene file changed after the plan was made.
  cp "$here/../../scenes/wall_crash.json" mine.json
  "$sandbox" sweep plan custom --scene mine.json "${small[@]}" --vary physics_hz=500 --out mine.jsonl > /dev/null ||
    fail "plan of mine.json"
  sed -i 's/"mass_kg": 1500/"mass_kg": 1400/' mine.json
  out=$("$sandbox" sweep run mine.jsonl --strict --out mine 2>&1)
  [[ $? -eq 2 && $out == *"mine.json has changed since the plan"* ]] || fail "a changed scene not noticed: $out"
  echo "sweep refusals, failures, provenance: ok"
}
small=(--set duration_s=0.25 --set 'vehicle.mesh=builtin:sedan?vertices=2000')
if [[ $part == refusals ]]; then  # in a folder of its own beside the resume part's, from its plan and clean run
  cd "$work" && [[ -s plan.jsonl && -d clean/cases ]] || fail "$work: no plan and clean run (the resume part first)"
  rm -rf refusals && mkdir refusals && cp -r plan.jsonl clean refusals/ && cd refusals || exit 1
  refusals
  exit 0
fi
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

# Cases of about half a second each here (the shipped wall crash), so that the kill lands halfway.
"$sandbox" sweep plan custom --scene wall_crash --vary vehicle.start.speed_kmh=20,40,56 \
  --vary vehicle.deformation.control_points=250,500 --out plan.jsonl > /dev/null || fail "plan"
[[ $(wc -l < plan.jsonl) -eq 7 ]] || fail "plan.jsonl: expected a header and 6 cases"

# A clean run in two shards, one after the other, then merged.
"$sandbox" sweep run plan.jsonl --shard 1/2 --out clean > /dev/null || fail "clean shard 1/2"
"$sandbox" sweep run plan.jsonl --shard 2/2 --out clean > /dev/null || fail "clean shard 2/2"
"$sandbox" sweep merge clean --out clean_result > /dev/null || fail "merge of the clean run"

# One shard killed once two results are written, then run again.
"$sandbox" sweep run plan.jsonl --out killed > killed_first.log 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [[ $(ls killed/cases 2>/dev/null | grep -c '\.json$') -ge 2 ]] && break
  sleep 0.05
done
kill -KILL "$pid" 2> /dev/null
wait "$pid" 2> /dev/null
done_before=$(ls killed/cases | grep -c '\.json$')
[[ $done_before -ge 2 && $done_before -lt 6 ]] || fail "expected the kill halfway, found $done_before results"
# A write cut short leaves at most a temporary file: put one there, and a torn result the run must redo.
echo '{"case": "00' > "killed/cases/0005.json.tmp.99999"
last=$(printf '%04d' $((done_before - 1)))
stamp_before=$(for f in killed/cases/*.json; do [[ $f == *"/$last.json" ]] || stat -c '%n %i %Y' "$f"; done)
head -c 20 "killed/cases/$last.json" > torn && mv torn "killed/cases/$last.json"
"$sandbox" sweep run plan.jsonl --out killed > killed_again.log 2>&1 || fail "the re-run: $(tail -3 killed_again.log)"
expected_kept=$((done_before - 1))
grep -q "6 cases, $((6 - expected_kept)) run, $expected_kept already done, 0 failed" killed_again.log ||
  fail "the re-run did not skip exactly the $expected_kept whole results: $(tail -1 killed_again.log)"
stamp_after=$(for f in killed/cases/*.json; do [[ $f == *"/$last.json" ]] || stat -c '%n %i %Y' "$f"; done)
kept_after=$(grep -F -f <(echo "$stamp_before" | cut -d' ' -f1) <<< "$stamp_after")
[[ "$stamp_before" == "$kept_after" ]] || fail "a kept result was rewritten"
[[ $(ls killed/cases | grep -c '\.json$') -eq 6 ]] || fail "expected 6 results after the re-run"
"$sandbox" sweep merge killed --out killed_result > /dev/null || fail "merge of the resumed run"
[[ $(cut -d, -f1 killed_result/sweep.csv | tail -n +2 | sort -u | wc -l) -eq 6 ]] || fail "merged cases not 6 distinct"
same_measures clean_result/sweep.csv killed_result/sweep.csv

echo "sweep resume: killed halfway and run again, no case lost or run twice; the merge equals a clean run's"
