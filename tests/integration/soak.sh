#!/usr/bin/env bash
# Soak: back-to-back realtime jobs at 1 kHz on two axes for DURATION seconds (an hour before a
# release), with a watcher on every job and an in-process sweep client beside them, the server on
# its job store. Every minute: the deadline misses of the jobs that ended, the RSS and open file
# descriptors of every process, the store's size. Passes when no job failed and the RSS of the
# server and of each node at the end is within 5 % of the first minute's (after warm-up).
# Usage: soak.sh BUILD_DIR DURATION_S [REPORT_FILE]   (loopback only; label soak, not in CI)
source "$(dirname "$0")/lib.sh" "$@"
duration_s=$2
report=${3:-/dev/null}
now_s() { date +%s; }
# As a lab deploys realtime: the loops under SCHED_FIFO with their memory locked (root here);
# the sweep client and everything else on the host under the normal scheduler.
rt=(--rt-priority 80 --lock-memory)

start x "$netmc_axis" --node soak-x --axes x --clock realtime --domain "$domain" --transport udp \
  --command-limit 5 "${rt[@]}"
x_pid=${pids[-1]}
start y "$netmc_axis" --node soak-y --axes y --clock realtime --domain "$domain" --transport udp \
  --command-limit 5 "${rt[@]}"
y_pid=${pids[-1]}
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --state-dir "$tmp/state" "${rt[@]}"
server_pid=${pids[-1]}
port=$(server_port 127.0.0.1)
server=(--server "127.0.0.1:$port")
job=(--clock realtime --controller adrc+ilccc --sample-period 1ms --duration 4s --iterations 5 --delay none)

rss_kib() { awk '/^VmRSS/ { print $2 }' "/proc/$1/status"; }
fds() { ls "/proc/$1/fd" | wc -l; }
sample() {  # MINUTE
  printf '%6s %10s %10s %10s %6s %6s %6s %10s %8s %8s %8s\n' "$1" "$(rss_kib "$server_pid")" "$(rss_kib "$x_pid")" \
    "$(rss_kib "$y_pid")" "$(fds "$server_pid")" "$(fds "$x_pid")" "$(fds "$y_pid")" \
    "$(du -k "$tmp/state" | cut -f1)" "$jobs_done" "$misses_minute" "$failed"
}

# The sweep client: in-process sweeps, every few seconds, for the whole run.
( while :; do
    nice -n 10 "$netmc" sweep --quiet --delay-max 0.5ms:5ms:4 --iterations 3 --csv "$tmp/sweep.csv" >/dev/null 2>&1 || true
    sleep 5
  done ) &
sweeper=$!
pids+=("$sweeper")

jobs_done=0
failed=0
misses_minute=0
misses_total=0
cycles_total=0
header=$(printf '%6s %10s %10s %10s %6s %6s %6s %10s %8s %8s %8s' minute "server KiB" "x KiB" "y KiB" "fd s" "fd x" \
  "fd y" "store KiB" jobs misses failed)
echo "$header" | tee "$report"
began=$(now_s)
next_sample=$((began + 60))
minute=0
while [ "$(now_s)" -lt $((began + duration_s)) ]; do
  n=$((jobs_done + failed + 1))
  # A watcher follows the job from another connection.
  id=$("$netmc" submit "${server[@]}" --quiet "${job[@]}")
  "$netmc" watch "$id" "${server[@]}" --quiet >/dev/null 2>&1 &
  watcher=$!
  if "$netmc" watch "$id" "${server[@]}" --quiet --json "$tmp/job.json" >/dev/null 2>"$tmp/job.err"; then
    jobs_done=$((jobs_done + 1))
    m=$(sed -n 's/.*"deadline_misses": \([0-9]*\).*/\1/p' "$tmp/job.json" | awk '{ s += $1 } END { print s + 0 }')
    misses_minute=$((misses_minute + m))
    misses_total=$((misses_total + m))
    cycles_total=$((cycles_total + 5 * 4001))
  else
    failed=$((failed + 1))
    echo "job $id ($n) failed: $(tail -1 "$tmp/job.err")" | tee -a "$report"
    # A tripped axis stays in fault until reset: reset it, so that one trip is one failed job.
    "$netmc" reset soak-x "${server[@]}" >/dev/null 2>&1 || true
    "$netmc" reset soak-y "${server[@]}" >/dev/null 2>&1 || true
  fi
  wait "$watcher" || true
  if [ "$(now_s)" -ge "$next_sample" ]; then
    minute=$((minute + 1))
    sample "$minute" | tee -a "$report"
    [ "$minute" -eq 1 ] && { first_server=$(rss_kib "$server_pid"); first_x=$(rss_kib "$x_pid"); first_y=$(rss_kib "$y_pid"); }
    misses_minute=0
    next_sample=$((next_sample + 60))
  fi
done
sample end | tee -a "$report"
kill "$sweeper" 2>/dev/null || true
{
  echo "$jobs_done jobs done, $failed failed, $misses_total deadline misses of $cycles_total cycles in $(( $(now_s) - began )) s"
  echo "RSS after the first minute -> end: server ${first_server:-?} -> $(rss_kib "$server_pid") KiB," \
    "x ${first_x:-?} -> $(rss_kib "$x_pid") KiB, y ${first_y:-?} -> $(rss_kib "$y_pid") KiB"
} | tee -a "$report"
[ "$failed" -eq 0 ] || { echo "FAIL: $failed jobs failed"; exit 1; }
if [ -n "${first_server:-}" ]; then
  for pair in "server:$first_server:$server_pid" "x:$first_x:$x_pid" "y:$first_y:$y_pid"; do
    IFS=: read -r name first pid <<<"$pair"
    now=$(rss_kib "$pid")
    [ $((now * 100)) -le $((first * 105)) ] || { echo "FAIL: $name grew from $first to $now KiB (more than 5 %)"; exit 1; }
  done
fi
echo "soak: passed"
