#!/usr/bin/env bash
# tools/test_budget.sh BUILD_DIR [BUDGET_S]: after a ctest run in BUILD_DIR, fails naming every test whose
# wall time went over BUDGET_S seconds (default 60), and prints the slowest five either way. `make test-asan`
# (CI) runs it on the sanitizer suite, so that no single test can eat CI's headroom (docs/GUIDE.md, "CI
# jobs"). The times are ctest's own (Testing/Temporary/LastTest.log), each test's wall time in a `ctest -j`
# run.
set -euo pipefail
log=$1/Testing/Temporary/LastTest.log
budget=${2:-60}
[[ -s $log ]] || { echo "test budget: no $log (run ctest first)" >&2; exit 2; }
times=$(awk '/^[0-9]+\/[0-9]+ Test: / { sub(/^[0-9]+\/[0-9]+ Test: /, ""); name = $0 }
             /^Test time = / { printf "%.1f %s\n", $4, name }' "$log" | sort -rn)
[[ -n $times ]] || { echo "test budget: no test times in $log (has ctest's log format changed?)" >&2; exit 2; }
echo "test budget: the slowest tests in $1 (budget ${budget} s each):"
head -5 <<< "$times" | sed 's/^/test budget:   /'
over=$(awk -v b="$budget" '$1 > b' <<< "$times")
if [[ -n $over ]]; then
  echo "test budget: over ${budget} s (make the test smaller under the sanitizers, or split it):" >&2
  sed 's/^/test budget:   /' <<< "$over" >&2
  exit 1
fi
