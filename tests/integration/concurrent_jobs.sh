#!/usr/bin/env bash
# Several jobs on one netmc-server at once, on loopback. One node hosts the axes of two machines
# (m1.x, m1.y, m2.x, m2.y):
#   - two lockstep jobs on disjoint axes run at the same time (the server's log shows both
#     running before either is done) and each equals `netmc sim` byte for byte;
#   - a third job for axes that a running job holds waits in the queue and starts only after
#     that job is done, then equals `netmc sim` too;
#   - realtime: four two-axis jobs at 1 kHz at once on two nodes all finish, with deadline misses
#     under a generous 50 % (eight 1 kHz axes and four loops on 2 cores of a virtual machine: one
#     run gave 31 % on a job; the figures that matter are measured by bench/realtime_sweep.sh).
# Usage: concurrent_jobs.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
axis_bin=$netmc_axis

start node "$axis_bin" --node machines --axes m1.x,m1.y,m2.x,m2.y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
port=$(server_port 127.0.0.1)
study=(--controller adrc+ilccc --iterations 6)

"$netmc" run --server "127.0.0.1:$port" --quiet --axes m1.x,m1.y "${study[@]}" --json "$tmp/a.json" >/dev/null &
run_a=$!
"$netmc" run --server "127.0.0.1:$port" --quiet --axes m2.x,m2.y "${study[@]}" --json "$tmp/b.json" >/dev/null &
run_b=$!
# The third is submitted once both are running, for the axes of the first.
for _ in $(seq 200); do
  [ "$(grep -c ' running on axes ' "$tmp/server.log" || true)" -ge 2 ] && break
  sleep 0.05
done
"$netmc" run --server "127.0.0.1:$port" --quiet --axes m1.x,m1.y "${study[@]}" --json "$tmp/c.json" >/dev/null &
run_c=$!
wait "$run_a"
wait "$run_b"
wait "$run_c"
grep -E 'netmc-server: job [0-9]+ ' "$tmp/server.log"

# Server log order: the two first jobs both running before either is done; the third (the axes
# of the first m1 job) starts only after that job is done.
id_on() { grep -E "netmc-server: job [0-9]+ running on axes $1 " "$tmp/server.log" | sed -n "$2s/.*netmc-server: job \([0-9]*\) .*/\1/p"; }
line() { grep -n -m1 -E "netmc-server: job $1 $2" "$tmp/server.log" | cut -d: -f1; }
first=$(id_on m1.x,m1.y 1)
other=$(id_on m2.x,m2.y 1)
third=$(id_on m1.x,m1.y 2)
[ "$(line "$first" running)" -lt "$(line "$other" done)" ] && [ "$(line "$other" running)" -lt "$(line "$first" done)" ] ||
  { echo "FAIL: the jobs on m1 and m2 did not run at the same time"; exit 1; }
echo "jobs $first (m1) and $other (m2) ran at the same time (both running before either was done)"
[ "$(line "$third" running)" -gt "$(line "$first" done)" ] || { echo "FAIL: job $third started while job $first held m1"; exit 1; }
echo "job $third (m1 again) waited in the queue until job $first was done"

"$netmc" sim "${study[@]}" --json "$tmp/sim.json" >/dev/null
for j in a b c; do
  cmp -s "$tmp/$j.json" "$tmp/sim.json" || { echo "FAIL: job $j differs from netmc sim"; diff "$tmp/sim.json" "$tmp/$j.json" | head; exit 1; }
done
echo "all three equal netmc sim byte for byte ($(wc -c <"$tmp/sim.json") bytes of JSON)"

# Realtime: four two-axis jobs at 1 kHz at once, on two nodes of four axes each.
start rt1 "$axis_bin" --node rt1 --axes r0,r1,r2,r3 --clock realtime --domain "$domain" --transport udp
start rt2 "$axis_bin" --node rt2 --axes r4,r5,r6,r7 --clock realtime --domain "$domain" --transport udp
runs=()
for j in 0 1 2 3; do
  "$netmc" run --server "127.0.0.1:$port" --quiet --clock realtime --axes "r$((2 * j)),r$((2 * j + 1))" \
    --controller adrc+ilccc --sample-period 1ms --duration 2s --iterations 2 --delay none \
    --json "$tmp/rt$j.json" >/dev/null &
  runs+=($!)
done
for pid in "${runs[@]}"; do wait "$pid"; done
total=0
for j in 0 1 2 3; do
  misses=$(sed -n 's/.*"deadline_misses": \([0-9]*\).*/\1/p' "$tmp/rt$j.json" | awk '{ s += $1 } END { print s }')
  total=$((total + misses))
  echo "realtime job $j: $misses deadline misses of 4002 cycles"
  [ "$misses" -lt 2000 ] || { echo "FAIL: more than 50 % deadline misses"; exit 1; }
done
echo "four realtime jobs at 1 kHz at once: $total deadline misses of 16008 cycles"
