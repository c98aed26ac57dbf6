#!/usr/bin/env bash
# A step of the wall clock (CLOCK_REALTIME) on axis x's host during a realtime job, once with the
# default --time-base monotonic and once with --time-base realtime (server and both nodes).
# The machine's own wall clock is never touched: only node x's process sees the step, through
# libfaketime (package libfaketime) preloaded with FAKETIME_DONT_FAKE_MONOTONIC=1 (CLOCK_MONOTONIC
# stays the machine's) and an offset file it re-reads every second; the test writes +STEP into it
# 1.5 s into the job. Time namespaces cannot do this: they offset CLOCK_MONOTONIC and BOOTTIME,
# not CLOCK_REALTIME, and only before a process enters them (separate_clocks.sh covers unrelated
# monotonic clocks).
#   monotonic: the step changes nothing: the job completes, axis x takes all its samples in
#     every iteration (its "N samples" lines), and the server still measures x's clock offset
#     near 0 after the job;
#   realtime: the server measures x's offset as the step after the job (the hosts' wall clocks
#     now disagree by STEP); the job must either complete or fail with a reason naming axis x
#     (seen with +2 s: x quick-stops on its watchdog, which sees the jump, and the job then
#     fails on x's silence). Then the next job runs to completion, its schedule kept across the
#     disagreement by the measured offset.
# The nodes' watchdog is 200 ms, not the default 50: the subject here is the clock, and a host
# that holds a node up for 50 ms (seen once in CI, in the next job) trips a 50 ms watchdog however
# the clocks stand; the +2 s jump trips 200 ms as surely. chaos_partition and chaos_server_killed
# test the watchdog itself.
# Usage: chaos_clock_step.sh BUILD_DIR [STEP_SECONDS]   (skipped, 77, without libfaketime)
source "$(dirname "$0")/lib.sh" "$@"
step=${2:-2}
watchdog_ms=200
faketime_lib=""
for f in /usr/lib/*/faketime/libfaketimeMT.so.1 /usr/lib/faketime/libfaketimeMT.so.1; do
  [ -e "$f" ] && { faketime_lib=$f; break; }
done
[ -n "$faketime_lib" ] || { echo "skipped: libfaketime is not installed (package libfaketime)"; exit 77; }

# x_offset_ms: the server's measured offset of node step-x's clock, in ms (rounded).
x_offset_ms() {
  "$netmc" nodes --server "127.0.0.1:$port" --json | awk -F': ' '
    { v = $2; gsub(/[",]/, "", v) }
    /^ *"node":/ { n = v }
    /^ *"clock_offset_s":/ && n == "step-x" { printf "%d\n", v * 1000 }'
}

# cluster BASE: the server and both nodes on time base BASE, x's wall clock steppable.
cluster() {
  local base=$1 d=$2
  echo "+0" >"$tmp/x-clock"
  start "x-$base" env LD_PRELOAD="$faketime_lib" FAKETIME_TIMESTAMP_FILE="$tmp/x-clock" FAKETIME_CACHE_DURATION=1 \
    FAKETIME_DONT_FAKE_MONOTONIC=1 "$netmc_axis" --node step-x --axes x --clock realtime \
    --time-base "$base" --domain "$d" --transport udp --command-limit 5 --watchdog "$watchdog_ms"
  start "y-$base" "$netmc_axis" --node step-y --axes y --clock realtime --time-base "$base" \
    --domain "$d" --transport udp --command-limit 5 --watchdog "$watchdog_ms"
  start "server" "$netmc_server" --listen 127.0.0.1:0 --time-base "$base" --domain "$d" \
    --transport udp
  port=$(server_port 127.0.0.1)
  for _ in $(seq 100); do
    grep -q serving "$tmp/x-$base.log" && grep -q serving "$tmp/y-$base.log" && break
    sleep 0.1
  done
  sleep 3.5   # the server's clock probes (one per 100 ms, best of 32) fill their window
}
job() {  # TAG: a realtime job; sets job_status
  job_status=0
  timeout 120 "$netmc" run --server "127.0.0.1:$port" --clock realtime --controller adrc+ilccc --iterations 2 \
    --duration 3s --quiet --json "$tmp/$1.json" >"$tmp/$1.out" 2>&1 || job_status=$?
}

for base in monotonic realtime; do
  domain=$((domain + 1))
  cluster "$base" "$domain"
  before=$(x_offset_ms)
  ( sleep 1.5; echo "+$step" >"$tmp/x-clock" ) &
  stepper=$!
  job "step-$base"
  wait "$stepper"
  sleep 3.5
  after=$(x_offset_ms)
  samples=$(sed -n 's/.*axis x job 1 iteration [0-9]*: \([0-9]*\) samples.*/\1/p' "$tmp/x-$base.log" | paste -sd' ')
  stops=$(grep -c "axis x job 1 .*quick stop" "$tmp/x-$base.log" || true)
  echo "$base: x's wall clock stepped +$step s mid-job: job exit $job_status$(grep -m1 -o 'failed: .*' "$tmp/step-$base.out" | sed 's/^/ (/;s/$/)/'),"\
    "x's samples per iteration: ${samples:-none}, quick stops: $stops, x's measured offset ${before} ms before, ${after} ms after"
  if [ "$base" = monotonic ]; then
    [ "$job_status" -eq 0 ] || { echo "FAIL: monotonic: the job failed"; cat "$tmp/step-$base.out"; exit 1; }
    [ "$samples" = "601 601" ] || { echo "FAIL: monotonic: axis x took samples '$samples', not 601 per iteration"; exit 1; }
    [ "${after#-}" -lt 50 ] || { echo "FAIL: monotonic: x's offset moved to $after ms with its wall clock"; exit 1; }
  else
    off=$(( after - before - step * 1000 ))
    [ "${off#-}" -lt 100 ] || { echo "FAIL: realtime: x's measured offset moved by $((after - before)) ms, not +$step s"; exit 1; }
    if [ "$job_status" -ne 0 ]; then
      grep -q 'failed: axis x' "$tmp/step-$base.out" || { echo "FAIL: realtime: failed without naming axis x"; cat "$tmp/step-$base.out"; exit 1; }
    fi
    job "next-$base"
    [ "$job_status" -eq 0 ] || { echo "FAIL: realtime: the next job failed:"; tail -n 3 "$tmp/next-$base.out"; exit 1; }
    echo "realtime: the next job, with x's wall clock $step s ahead, completed"
  fi
  stop_all
done
