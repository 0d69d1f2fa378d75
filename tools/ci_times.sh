#!/usr/bin/env bash
# tools/ci_times.sh MAKE JOB...: `make ci`. Runs each job (a Makefile target) in order, stops at the first
# that fails, and prints each job's wall time at the end, the failed one's too: CI has a time limit
# (docs/GUIDE.md, "CI jobs"), and this shows which job is eating it.
set -uo pipefail
make_cmd=$1
shift
names=() times=() results=()
status=0
total_start=$(date +%s)
for job in "$@"; do
  start=$(date +%s)
  $make_cmd --no-print-directory "$job"
  status=$?
  names+=("$job") times+=($(($(date +%s) - start)))
  if [[ $status -ne 0 ]]; then
    results+=("failed")
    break
  fi
  results+=("passed")
done
minutes() { printf '%d min %02d s' $(($1 / 60)) $(($1 % 60)); }
echo "ci: job times"
for i in "${!names[@]}"; do
  printf 'ci:   %-10s %s  %s\n' "${names[$i]}" "$(minutes "${times[$i]}")" "${results[$i]}"
done
printf 'ci:   %-10s %s\n' total "$(minutes $(($(date +%s) - total_start)))"
exit $status
