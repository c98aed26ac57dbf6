#!/usr/bin/env bash
# Prints, for each test the last ctest run in BUILD_DIR failed, the end of its output (the lines
# that name the failure come last in netmc's tests: "FAIL: ...", gtest's "Failure" and its
# expected/actual lines). Usage: failed-tests-summary.sh BUILD_DIR [LINES]
set -euo pipefail
build=${1:?usage: failed-tests-summary.sh BUILD_DIR [LINES]}
lines=${2:-25}
failed=$build/Testing/Temporary/LastTestsFailed.log
log=$build/Testing/Temporary/LastTest.log
[ -s "$failed" ] && [ -f "$log" ] || exit 0
echo "=== the failed tests, the last $lines lines of each one's output"
cut -d: -f2- "$failed" | while IFS= read -r name; do
  echo "--- $name"
  # LastTest.log: each test's output sits between its 'Output:' rule and '<end of output>'.
  awk -v name="$name" '
    $0 ~ /^[0-9]+\/[0-9]+ Test: / { current = substr($0, index($0, ": ") + 2) }
    current == name && /^Output:/ { inside = 1; getline; next }
    inside && /^<end of output>/ { inside = 0; current = "" }
    inside { print }
  ' "$log" | grep -v '^$' | tail -n "$lines"
done
