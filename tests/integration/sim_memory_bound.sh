#!/usr/bin/env bash
# netmc sim's memory is bounded by what a job must keep, not by how long it runs: an iteration
# longer than 1e7 cycles is refused at once naming the field (200000 s at 5 ms died of
# std::bad_alloc at 4.5 GB), and a long iteration (1.2e6 cycles, past DelayStatistics' exact
# threshold) completes under an address-space cap with a bounded peak RSS.
# Usage: sim_memory_bound.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"

rc=0
timeout 30 "$netmc" sim -q --duration 200000s >"$tmp/long.txt" 2>&1 || rc=$?
[ "$rc" -eq 2 ] && grep -q "duration: expected at most 1e7 cycles per iteration" "$tmp/long.txt" ||
  { echo "FAIL: --duration 200000s was not refused at once (exit $rc):"; head -5 "$tmp/long.txt"; exit 1; }
echo "refused: $(cat "$tmp/long.txt")"

# 6000 s at 5 ms: 1.2e6 cycles, 2.4e6 loop delays of two axes (beyond the 2^21 kept exactly).
rc=0
prlimit --as=$((1024 * 1024 * 1024)) /usr/bin/time -v "$netmc" sim -q --controller adrc --duration 6000s \
  --json "$tmp/long.json" >"$tmp/run.txt" 2>&1 || rc=$?
[ "$rc" -eq 0 ] || { echo "FAIL: the 6000 s run did not complete under a 1 GiB address-space cap (exit $rc)"; tail -5 "$tmp/run.txt"; exit 1; }
rss_kib=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$tmp/run.txt")
echo "6000 s run: peak RSS ${rss_kib} KiB under a 1 GiB address-space cap"
limit_kib=262144  # 98.6 MB measured on 2026-11-26 (about 72 bytes a cycle, the delays binned)
[ "$rss_kib" -lt "$limit_kib" ] || { echo "FAIL: peak RSS ${rss_kib} KiB, expected under ${limit_kib} KiB"; exit 1; }
grep -q '"tau_p99_s"' "$tmp/long.json" || { echo "FAIL: no delay statistics in the result"; exit 1; }
