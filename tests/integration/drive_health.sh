#!/usr/bin/env bash
# A node tells the truth about its drives (loopback; a realtime node on two emulated Modbus drives,
# paper 001's X and Y axes):
#   1. x's emulator stopped while the node is idle: within 1 s `netmc nodes` shows the node in
#      fault naming the axis, the drive and the cause, and the axis's state "no answer"
#      (not a CiA 402 state it did not read); a job on it is refused at once, naming the axis and
#      the node; `netmc reset` exits non-zero naming the drive;
#   2. the emulator back and the node reset: the node is idle and ready, and a job runs.
# Usage: drive_health.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
emulator=$build/server/drive/emulator/netmc-drive-emulator
head -c 32 /dev/urandom | base64 >"$tmp/admin.token"
chmod 600 "$tmp/admin.token"

start drive "$emulator" --listen 127.0.0.1:0 --plant seed001 --axis 0 --initial-position 0.055
start drive-y "$emulator" --listen 127.0.0.1:0 --plant seed001 --axis 1 --initial-position 0.045
lab_wait_log drive 'listening on' 10
lab_wait_log drive-y 'listening on' 10
drive_port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/drive.log" | head -n 1)
drive_y_port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/drive-y.log" | head -n 1)
start node "$netmc_axis" --node bench --axes x,y --clock realtime --drive "x=modbus-tcp:127.0.0.1:$drive_port" \
  --drive "y=modbus-tcp:127.0.0.1:$drive_y_port" --command-limit 5 --position-window 0:0.12 --velocity-limit 0.5 \
  --domain "$domain" --transport udp
lab_wait_log node 'serving' 15
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --admin-token-file "$tmp/admin.token"
port=$(server_port 127.0.0.1)
lab_wait_log server 'node bench joined' 10
job=(--controller adrc --iterations 1 --trajectory circle:r=2mm,cx=55mm,cy=50mm,period=2s --clock realtime)
"$netmc" nodes --server "127.0.0.1:$port" --json >"$tmp/before.json"
grep -q '"health": "idle: ready"' "$tmp/before.json" || { cat "$tmp/before.json"; lab_fail "the node is not idle and ready"; }

# 1. The drive gone while idle.
lab_stop drive
stopped=$(date +%s.%N)
shown=""
for _ in $(seq 40); do
  "$netmc" nodes --server "127.0.0.1:$port" --json >"$tmp/nodes.json"
  if grep -q '"health": "fault: x: modbus-tcp:127.0.0.1:'"$drive_port"' unit 1: ' "$tmp/nodes.json"; then
    shown=$(date +%s.%N)
    break
  fi
  sleep 0.05
done
[ -n "$shown" ] || { cat "$tmp/nodes.json"; lab_fail "the node did not show the lost drive as a fault"; }
awk -v a="$stopped" -v b="$shown" 'BEGIN { ms = (b - a) * 1e3; printf "drive stopped: node in fault %.0f ms later\n", ms;
  exit ms <= 1000 ? 0 : 1 }' || lab_fail "the fault showed later than 1 s after the drive stopped"
grep -o '"health": "[^"]*"' "$tmp/nodes.json"
grep -q '"state": "no answer"' "$tmp/nodes.json" || lab_fail "the axis's state is not 'no answer' while its drive is gone"
grep -q 'retry\|tried again' "$tmp/nodes.json" && lab_fail "the node's health speaks of its retry timer"

refused=0
SECONDS=0
"$netmc" run --server "127.0.0.1:$port" "${job[@]}" --quiet >"$tmp/refused.txt" 2>&1 || refused=$?
[ "$refused" -ne 0 ] && grep -q "axis x is in fault: node bench reports x: modbus-tcp" "$tmp/refused.txt" ||
  { cat "$tmp/refused.txt"; lab_fail "a job on the faulted node was not refused naming it"; }
echo "job refused in ${SECONDS} s: $(grep -o 'axis x is in fault[^;]*' "$tmp/refused.txt" | head -n 1)"

reset=0
NETMC_TOKEN_FILE=$tmp/admin.token "$netmc" reset bench --server "127.0.0.1:$port" --wait 2000 >"$tmp/reset.txt" 2>&1 ||
  reset=$?
[ "$reset" -ne 0 ] && grep -q "modbus-tcp:127.0.0.1:$drive_port unit 1" "$tmp/reset.txt" ||
  { cat "$tmp/reset.txt"; lab_fail "netmc reset with the drive gone did not fail naming the drive"; }
echo "netmc reset: exit $reset: $(tail -n 1 "$tmp/reset.txt")"

# 2. The drive back, the node reset: ready, and the job runs.
start drive-2 "$emulator" --listen "127.0.0.1:$drive_port" --plant seed001 --axis 0 --initial-position 0.055
lab_wait_log drive-2 'master .* connected' 10 || lab_fail "the node did not reconnect to the restarted drive"
NETMC_TOKEN_FILE=$tmp/admin.token "$netmc" reset bench --server "127.0.0.1:$port" >"$tmp/reset-2.txt"
for _ in $(seq 40); do
  "$netmc" nodes --server "127.0.0.1:$port" --json >"$tmp/after.json"
  grep -q '"health": "idle: ' "$tmp/after.json" && break
  sleep 0.05
done
grep -q '"health": "idle: ' "$tmp/after.json" || { cat "$tmp/after.json"; lab_fail "the node is not idle after the reset"; }
"$netmc" run --server "127.0.0.1:$port" "${job[@]}" --quiet >"$tmp/after.txt" 2>&1 ||
  { cat "$tmp/after.txt"; lab_fail "the job after the drive came back failed"; }
echo "drive back, reset: $(grep -o '"health": "[^"]*"' "$tmp/after.json"); the job ran"
