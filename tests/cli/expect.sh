#!/usr/bin/env bash
# expect.sh CODE PATTERN COMMAND...: passes when COMMAND exits with CODE and its output (stdout and
# stderr together) matches the extended regular expression PATTERN. Used for the command-line contract:
# exit 0 done, 2 bad input, 1 failure inside, and one clear message naming the file or flag.
set -u
expected_code=$1
pattern=$2
shift 2
output=$("$@" 2>&1)
code=$?
if [[ $code -ne $expected_code ]]; then
  echo "expected exit $expected_code, got $code from: $*"
  echo "$output" | head -20
  exit 1
fi
if ! grep -Eq -- "$pattern" <<<"$output"; then
  echo "output of '$*' does not match /$pattern/:"
  echo "$output" | head -20
  exit 1
fi
lines=$(grep -c . <<<"$output")
if [[ $expected_code -eq 2 && $lines -gt 3 ]]; then
  echo "bad input should give one clear message, got $lines lines:"
  echo "$output" | head -20
  exit 1
fi
exit 0
