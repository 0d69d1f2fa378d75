#!/usr/bin/env bash
# stress_random.sh SANDBOX WORK: `sandbox stress --random 2 --seed 1 --out WORK` prints the table, a row per
# scene and the closing line "P passed, F failed", exits 1 exactly when a scene failed (0 otherwise), and
# writes the CSV and every failing scene as a scene file that `sandbox run` reads.
set -uo pipefail
sandbox=$1
work=$2
fail() {
  echo "stress --random: $*"
  exit 1
}
rm -rf "$work" && mkdir -p "$work" || exit 1
"$sandbox" stress --random 2 --seed 1 --out "$work" > "$work/stdout.txt" 2> "$work/stderr.txt"
code=$?
out=$(cat "$work/stdout.txt")
grep -Eq '^#  +cars +km/h +aimed at +Hz +preset +coupling +created% +car bal% +rise m +verdict +failed' <<<"$out" ||
  fail "no table header in: $out"
rows=$(grep -Ec '^[01] +[123] +[0-9/]+ ' <<<"$out")
[[ $rows -eq 2 ]] || fail "expected 2 rows, got $rows in: $out"
closing=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' <<<"$out") || fail "no closing line in: $out"
failed=$(sed -E 's/.* ([0-9]+) failed/\1/' <<<"$closing")
[[ $closing == "$((2 - failed)) passed, $failed failed" ]] || fail "the counts do not add up to 2: $closing"
if [[ $failed -gt 0 ]]; then
  [[ $code -eq 1 ]] || fail "$failed failed but exit $code"
else
  [[ $code -eq 0 ]] || fail "none failed but exit $code: $(cat "$work/stderr.txt")"
fi
[[ $(grep -c . "$work/stress_random.csv") -eq 3 ]] || fail "stress_random.csv: not a header and 2 rows"
for index in 0 1; do
  if grep -Eq "^$index +.* FAIL " <<<"$out"; then
    scene="$work/random_1_$index.json"
    [[ -f $scene ]] || fail "scene $index failed but $scene was not written"
    # The file reads as a scene (a run to 0.01 s: the reader's checks and the world's, not the whole run).
    "$sandbox" run "$scene" --set duration_s=0.01 --out "$work/run_$index" > /dev/null 2>&1 ||
      fail "sandbox run $scene refused it"
  fi
done
echo "stress --random 2 --seed 1: table, $closing, exit $code"
