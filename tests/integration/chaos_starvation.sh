#!/usr/bin/env bash
# CPU starvation and memory pressure during realtime jobs (loopback). The server is pinned to CPU 0
# and axis node x to CPU 1 (--cpus); both run under the normal scheduler (no --rt-priority, the
# default), so each competitor runs under the same policy and nice value, pinned to the same CPU
# (taskset). Phases, one realtime job (adrc+ilccc, 2 iterations of 3 s) each, the same server
# and nodes throughout:
#   quiet      no competitor: the reference counts;
#   busy       a busy loop on CPU 0 beside the server and one on CPU 1 beside axis x;
#   stalled    axis x stopped (SIGSTOP) for 0.3 s mid-job: 60 periods with no sample at all;
#   memory     a bounded hog on CPU 1: 1 GiB (at most a quarter of MemAvailable) allocated and
#              rewritten page by page without end (no machine-wide pressure: the OOM killer must
#              never be a risk to other work on the machine);
#   after      quiet again: the next job runs to completion (an attempt ended by a trip, which
#              the host's own stalls can cause in any realtime job here, is reset and repeated:
#              at most 3 attempts).
# Every phase: every process is still alive (nothing crashed), the job ends within 60 s, either
# completed (its JSON reports each iteration's deadline_misses, late_feedback and lost counts) or
# failed with a reason naming an axis (a tripped axis is reset with SIGUSR1 before the next job).
# The nodes' command limit is 5 (as in the other realtime tests on this noisy host: a stall makes
# ADRC ask up to 2.2 for a cycle; trips after stale feedback are chaos_partition's subject).
# The stall must be counted: at least 30 deadline misses (60 periods went by without feedback
# from x), or the job failed naming axis x.
# Usage: chaos_starvation.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
[ "$(nproc)" -ge 2 ] || { echo "skipped: needs 2 CPUs (server and axis on CPUs of their own)"; exit 77; }

start x "$netmc_axis" --node starve-x --axes x --clock realtime --domain "$domain" \
  --transport udp --cpus 1 --command-limit 5
x_pid=${pids[-1]}
start y "$netmc_axis" --node starve-y --axes y --clock realtime --domain "$domain" \
  --transport udp --command-limit 5
y_pid=${pids[-1]}
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp --cpus 0
server_pid=${pids[-1]}
port=$(server_port 127.0.0.1)
for _ in $(seq 100); do
  grep -q serving "$tmp/x.log" && grep -q serving "$tmp/y.log" && break
  sleep 0.1
done
# The competitors take the policy the node and the server really run under.
node_policy=$(chrt -p "$x_pid" | sed -n 's/.*scheduling policy: //p')
[ "$node_policy" = SCHED_OTHER ] || { echo "FAIL: axis x runs under $node_policy, not the default SCHED_OTHER"; exit 1; }

all_alive() {
  local what pid
  for what in x:$x_pid y:$y_pid server:$server_pid; do
    pid=${what#*:}
    kill -0 "$pid" 2>/dev/null || { echo "FAIL: ${what%%:*} died during phase $1:"; tail -n 20 "$tmp/${what%%:*}.log"; exit 1; }
  done
}
# counts JSON KEY: the KEY of every iteration, space-separated.
counts() { sed -n "s/.*\"$2\": \\([0-9]*\\),*\$/\\1/p" "$1" | paste -sd' '; }
total() { counts "$1" "$2" | tr ' ' '\n' | awk '{ s += $1 } END { print s + 0 }'; }

# run_phase NAME: the job in the background (so a phase can act during it); phase_end NAME
# waits for it and checks the outcome.
run_phase() {
  "$netmc" run --server "127.0.0.1:$port" --clock realtime --controller adrc+ilccc --iterations 2 \
    --duration 3s --quiet --json "$tmp/$1.json" >"$tmp/$1.out" 2>&1 &
  job_pid=$!
}
phase_end() {
  local name=$1 st=0 reason tripped
  for _ in $(seq 600); do kill -0 "$job_pid" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$job_pid" 2>/dev/null; then echo "FAIL: $name: the job did not end within 60 s"; exit 1; fi
  wait "$job_pid" || st=$?
  all_alive "$name"
  if [ "$st" -eq 0 ]; then
    grep -q '"deadline_misses"' "$tmp/$name.json" || { echo "FAIL: $name: no deadline_misses in the result"; exit 1; }
    misses=$(total "$tmp/$name.json" deadline_misses)
    echo "$name: completed; per iteration deadline misses $(counts "$tmp/$name.json" deadline_misses)," \
      "late feedback $(counts "$tmp/$name.json" late_feedback), lost feedback $(counts "$tmp/$name.json" lost_feedback)," \
      "lost setpoints $(counts "$tmp/$name.json" lost_setpoints)$(grep -c "quick stop" "$tmp/x.log" | sed 's/^/; quick stops of x so far: /')"
    return 0
  fi
  reason=$(grep -m1 -o 'failed: axis [xy] .*' "$tmp/$name.out" || true)
  [ -n "$reason" ] || { echo "FAIL: $name: the job failed without a reason naming an axis:"; cat "$tmp/$name.out"; exit 1; }
  misses=failed
  echo "$name: job ${reason}"
  tripped=$(grep -o 'axis [xy] tripped' <<<"$reason" | head -n 1 | cut -d' ' -f2 || true)
  if [ -n "$tripped" ]; then
    kill -USR1 "$([ "$tripped" = x ] && echo "$x_pid" || echo "$y_pid")"   # the operator's reset
    sleep 1
  fi
}

run_phase quiet; phase_end quiet

start busy0 taskset -c 0 bash -c 'while :; do :; done'
busy0=${pids[-1]}
start busy1 taskset -c 1 bash -c 'while :; do :; done'
busy1=${pids[-1]}
run_phase busy; phase_end busy
kill "$busy0" "$busy1"

run_phase stalled
sleep 1.5
kill -STOP "$x_pid"; sleep 0.3; kill -CONT "$x_pid"
phase_end stalled
if [ "$misses" != failed ] && [ "$misses" -lt 30 ]; then
  echo "FAIL: axis x stopped for 0.3 s (60 periods), but only $misses deadline misses counted"; exit 1
fi

hog_mib=$(awk '/MemAvailable/ { m = int($2 / 1024 / 4); print (m < 1024) ? m : 1024 }' /proc/meminfo)
start memory taskset -c 1 /usr/bin/python3 -c "
import sys
size = $hog_mib << 20
block = bytearray(size)
print('holding', size >> 20, 'MiB', flush=True)
while True:
    for i in range(0, size, 4096):
        block[i] = (block[i] + 1) & 255
"
for _ in $(seq 100); do grep -q holding "$tmp/memory.log" && break; sleep 0.1; done
grep -q holding "$tmp/memory.log" || { echo "FAIL: the memory hog did not start:"; cat "$tmp/memory.log"; exit 1; }
hog_rss=$(awk '/VmRSS/ { print int($2 / 1024) }' "/proc/${pids[-1]}/status")
run_phase memory; phase_end memory
echo "memory: the hog held $hog_rss MiB resident"
kill "${pids[-1]}"

# This 2-core VM is shared: its own stalls (tens of ms) can trip an axis in any realtime job, also
# a quiet one. The next job must complete; an attempt that ended in a trip (reset above) may be
# followed by another, at most 3 in all, never by a failure of another kind.
for attempt in 1 2 3; do
  run_phase after; phase_end after
  [ "$misses" = failed ] || break
  grep -q 'tripped' "$tmp/after.out" || { echo "FAIL: the job after the starvation phases failed"; exit 1; }
done
[ "$misses" != failed ] || { echo "FAIL: the job after the starvation phases failed 3 times"; exit 1; }
echo "after: completed at attempt $attempt"
