#!/usr/bin/env bash
# A lab-sized domain on loopback: 20 axis nodes (10 two-axis machines p0..p9, one axis per node),
# 15 consecutive jobs on one server with every job's iteration logs checked on the DDS topic,
# then two servers on the same domain running a job each on their own axes at the same time, and
# a third job refused because its axes are held by the other server. While they run, no netmc
# socket may be bound to anything but loopback (ss).
# Usage: many_nodes.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
source "$(dirname "$0")/lab.sh"
axis_bin=$netmc_axis
server_bin=$netmc_server

for i in $(seq 0 19); do
  machine=p$((i / 2))
  axis=$([ $((i % 2)) -eq 0 ] && echo x || echo y)
  lab_start "node$i" - -- "$axis_bin" --node "n$i" --axes "$machine.$axis" --domain "$domain" --transport udp
done
lab_start listener - -- "$build/tests/integration/netmc_iteration_log_listener" --domain "$domain" --seconds 240
lab_start serverA - -- "$server_bin" --listen 127.0.0.1:0 --domain "$domain" --transport udp
lab_wait_log serverA 'listening on' 10
portA=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/serverA.log")
serverA=$(sed -n 's/.*, server \([0-9a-f]*\),.*/\1/p' "$tmp/serverA.log")

# Every node listed (each waits 1.5 s for a rival claim before it serves).
listed=0
for _ in $(seq 100); do
  listed=$("$netmc" nodes --server "127.0.0.1:$portA" --json | { grep -o '"node":' || true; } | wc -l)
  [ "$listed" -eq 20 ] && break
  sleep 0.1
done
"$netmc" nodes --server "127.0.0.1:$portA" >"$tmp/nodes.txt"  # whole: a pipe to head may end it early
head -4 "$tmp/nodes.txt"
echo "netmc nodes lists $listed of 20 nodes"
[ "$listed" -eq 20 ] || { echo "FAIL: expected 20 nodes"; exit 1; }

assert_loopback_only 'netmc'
echo "every netmc socket is on loopback (ss)"

start_s=$(date +%s.%N)
for j in $(seq 1 15); do
  m=p$((j % 10))
  "$netmc" run --server "127.0.0.1:$portA" --quiet --axes "$m.x,$m.y" --controller adrc --iterations 2 \
    --duration 0.5s >/dev/null || { echo "FAIL: job $j on $m failed"; exit 1; }
done
echo "15 consecutive jobs done in $(awk -v a="$start_s" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s"
for _ in $(seq 50); do
  logs=$(grep -c "^$serverA " "$tmp/listener.log" || true)
  [ "$logs" -ge 30 ] && break
  sleep 0.1
done
jobs_logged=$(grep "^$serverA " "$tmp/listener.log" | awk '{print $2}' | sort -un | wc -l)
echo "iteration logs on the DDS topic: $logs samples from $jobs_logged jobs (expected 30 from 15)"
[ "$logs" -eq 30 ] && [ "$jobs_logged" -eq 15 ] || { echo "FAIL: iteration logs missing"; exit 1; }

# A second server on the same domain; each runs a job on its own axes at the same time.
lab_start serverB - -- "$server_bin" --listen 127.0.0.1:0 --domain "$domain" --transport udp --hold-wait 0
lab_wait_log serverB 'listening on' 10
portB=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/serverB.log")
serverB=$(sed -n 's/.*, server \([0-9a-f]*\),.*/\1/p' "$tmp/serverB.log")
study=(--controller adrc+ilccc --iterations 8)
"$netmc" run --server "127.0.0.1:$portA" --quiet --axes p0.x,p0.y "${study[@]}" --json "$tmp/a.json" >/dev/null &
run_a=$!
"$netmc" run --server "127.0.0.1:$portB" --quiet --axes p1.x,p1.y "${study[@]}" --json "$tmp/b.json" >/dev/null &
run_b=$!
# While both run: each machine is held by its own server, and server B cannot take p0.
held=""
for _ in $(seq 100); do
  # Server A names itself "this server" and B by its GUID prefix.
  held=$("$netmc" nodes --server "127.0.0.1:$portA" | grep -cE "held by (this server|$serverB) " || true)
  [ "$held" -ge 4 ] && break
  sleep 0.05
done
"$netmc" nodes --server "127.0.0.1:$portA" | grep -E '^n[0-3] ' || true
set +e
wait "$run_a"; rc_a=$?
wait "$run_b"; rc_b=$?
set -e
echo "jobs at the same time: server A on p0 exit $rc_a, server B on p1 exit $rc_b; nodes held during them: $held of 4"
[ "$rc_a" -eq 0 ] && [ "$rc_b" -eq 0 ] || { echo "FAIL: a concurrent job failed"; exit 1; }
[ "$held" -ge 4 ] || { echo "FAIL: the four nodes were not seen held by their servers"; exit 1; }
"$netmc" sim --quiet "${study[@]}" --json "$tmp/sim.json" >/dev/null
cmp -s "$tmp/a.json" "$tmp/sim.json" && cmp -s "$tmp/b.json" "$tmp/sim.json" ||
  { echo "FAIL: concurrent jobs differ from netmc sim"; exit 1; }
echo "both equal netmc sim byte for byte"

# While server A holds p2, server B may not take it: refused, with the holder named.
"$netmc" run --server "127.0.0.1:$portA" --quiet --axes p2.x,p2.y "${study[@]}" >/dev/null &
run_a=$!
for _ in $(seq 200); do
  "$netmc" nodes --server "127.0.0.1:$portB" | grep -qE "^n4 .*held by $serverA" && break
  sleep 0.05
done
set +e
"$netmc" run --server "127.0.0.1:$portB" --quiet --axes p2.x,p2.y --controller adrc --iterations 1 \
  >/dev/null 2>"$tmp/refused.err"
refused_rc=$?
wait "$run_a"; rc_a=$?
set -e
echo "server B on axes held by server A: exit $refused_rc: $(tail -n 1 "$tmp/refused.err")"
[ "$refused_rc" -ne 0 ] && grep -q "held by server $serverA" "$tmp/refused.err" ||
  { echo "FAIL: the job on held axes was not refused with the holder named"; exit 1; }
[ "$rc_a" -eq 0 ] || { echo "FAIL: server A's job on p2 failed"; exit 1; }
