#!/usr/bin/env bash
# A whole job through a real fieldbus, inside a private network namespace (its loopback only):
# netmc-server -> DDS -> netmc-axis -> Modbus TCP -> two netmc-drive-emulator processes hosting
# paper 001's axes (seed001 X and Y, starting away from the contour's start).
#   1. realtime adrc+ilccc at h = 5 ms (paper 001's rate), 5 iterations: e_sum falls by >= 80 %
#      and e_max is 0.5-3 times netmc sim's for the same study (host stalls); the axes are moved
#      to the start through CiA 402 and CSP before every iteration.
#   2. the server killed mid-job: each drive sees a quick stop within the node's 100 ms watchdog
#      (bound 250 ms; 100 ms, not the default 50, so that a host stall of this 2-core virtual
#      machine during step 1's 40 s of realtime control is no trip), comes to standstill, and the node reports Quick stop active, then Switch on
#      disabled.
#   3. a position-window trip: Fault on the drive's axis; netmc reset without the admin token is
#      refused, with it the axis leaves Fault, and the next job (back inside the window) runs.
#   4. the emulator killed mid-job: the axis trips naming the cause; restarted and reset, the next
#      job runs. 5. an emulator answering Modbus exceptions: the axis trips naming the exception.
# Usage: modbus_drive.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
source "$(dirname "$0")/lab.sh"
lab_keep_logs
emulator=$build/server/drive/emulator/netmc-drive-emulator
axis_bin=$netmc_axis
server_bin=$netmc_server

lab_init
lab_host rig
head -c 32 /dev/urandom | base64 >"$tmp/admin.token"
chmod 600 "$tmp/admin.token"

port_of() { sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/$1.log" | head -n 1; }
# emulate NAME AXIS INITIAL_POSITION [PORT] [FLAGS...]: a drive for seed001's axis AXIS.
emulate() {
  local name=$1 axis=$2 at=$3 port=${4:-0}
  shift 4 || shift $#
  lab_start "$name" rig -- "$emulator" --listen "127.0.0.1:$port" --plant seed001 --axis "$axis" \
    --initial-position "$at" "$@"
  lab_wait_log "$name" 'listening on' 10
}
emulate drive-x 0 0.055 0
emulate drive-y 1 0.045 0
px=$(port_of drive-x)
py=$(port_of drive-y)
# node LOGNAME [WINDOW]: the axis node on both drives (their limits are the operator's: required).
# Command limit 5 (the rated input is 1): a host stall of tens of ms on this virtual machine can
# make ADRC ask for twice the rated input for a cycle; the window is the limit these tests trip.
node() {
  lab_start "$1" rig -- "$axis_bin" --node rig --axes x,y --clock realtime --transport udp \
    --drive "x=modbus-tcp:127.0.0.1:$px" --drive "y=modbus-tcp:127.0.0.1:$py" \
    --command-limit 5 --position-window "${2:-0:0.12}" --velocity-limit 0.5 --watchdog 100
  lab_wait_log "$1" 'serving' 15
}
# server LOGNAME: netmc-server with an admin token; its port in $port.
server() {
  lab_start "$1" rig -- "$server_bin" --listen 127.0.0.1:0 --transport udp --admin-token-file "$tmp/admin.token"
  lab_wait_log "$1" 'listening on' 10
  port=$(port_of "$1")
}
# Refused at the start, before the node joins the domain: a malformed map, an unknown register,
# a scale out of range, an unreachable drive.
cat >"$tmp/bad-map.json" <<'JSON'
{ "format": "netmc-modbus-map", "version": 1, "unit_id": 1, "high_word_first": true, "job_mode": "cst",
  "registers": { "statusword": { "address": 0, "type": "uint16" }, "torque_demand": { "address": 9, "type": "int16" } } }
JSON
sed '/"position_actual"/ s/"scale": 1e9/"scale": 0/' "$(dirname "$0")/../../server/drive/modbus/default-map.json" \
  >"$tmp/zero-scale.json"
printf '{ "format": "netmc-modbus-map", ' >"$tmp/truncated.json"
refused() {  # refused WHAT DRIVE_SPEC EXPECTED_TEXT
  local status=0
  lab_exec rig -- "$axis_bin" --node refused --axes x --clock realtime --command-limit 1 --position-window 0:0.1 \
    --velocity-limit 0.5 --drive "x=$2" >"$tmp/refused.log" 2>&1 || status=$?
  [ "$status" -eq 2 ] && grep -q -- "$3" "$tmp/refused.log" || lab_fail "$1: exit $status, $(cat "$tmp/refused.log")"
  echo "refused at start, $1: $(grep -o 'error: .*' "$tmp/refused.log" | cut -c1-150)"
}
refused "unknown register" "modbus-tcp:127.0.0.1:$px,map=$tmp/bad-map.json" "torque_demand"
refused "zero scale" "modbus-tcp:127.0.0.1:$px,map=$tmp/zero-scale.json" "registers.position_actual.scale"
refused "malformed map" "modbus-tcp:127.0.0.1:$px,map=$tmp/truncated.json" "truncated.json"
refused "unreachable drive" "modbus-tcp:127.0.0.1:1" "127.0.0.1:1"
refused "bad unit" "modbus-tcp:127.0.0.1:$px,unit=300" "unit"
node node
server server
lab_exec rig -- "$netmc" nodes --server "127.0.0.1:$port" | grep -q '^refused ' && lab_fail "a refused node joined the domain"

run() { lab_exec rig -- "$netmc" run --server "127.0.0.1:$port" --clock realtime "$@"; }
small=(--controller adrc --iterations 1 --trajectory circle:r=2mm,cx=55mm,cy=50mm,period=2s)

# 1. Paper 001's study through the fieldbus, against netmc sim.
run --controller adrc+ilccc --iterations 5 --json "$tmp/modbus.json" --quiet >/dev/null
"$netmc" sim --controller adrc+ilccc --iterations 5 --json "$tmp/sim.json" --quiet >/dev/null
python3 - "$tmp/modbus.json" "$tmp/sim.json" <<'PY'
import json, sys
modbus = json.load(open(sys.argv[1]))["runs"][0]["iterations"]
sim = json.load(open(sys.argv[2]))["runs"][0]["iterations"]
cut = 1 - modbus[-1]["e_sum_m"] / modbus[0]["e_sum_m"]
ratio = modbus[-1]["e_max_m"] / sim[-1]["e_max_m"]
misses = sum(i["deadline_misses"] for i in modbus)
print(f"modbus: e_sum {modbus[0]['e_sum_m']*1e3:.3f} -> {modbus[-1]['e_sum_m']*1e3:.3f} mm (cut {cut*100:.1f} %), "
      f"e_max {modbus[-1]['e_max_m']*1e6:.2f} um (netmc sim {sim[-1]['e_max_m']*1e6:.2f} um, ratio {ratio:.3f}), "
      f"{misses} deadline misses in {len(modbus)} iterations")
sys.exit(0 if cut >= 0.80 and 0.5 <= ratio <= 3.0 else 1)  # generous: real delays, host stalls
PY
grep -o 'modbus round trip p50 [^,]*, p99 [^,]*' "$tmp/node.log" | tail -n 1 | sed 's/^/  node, last iteration: /'
grep -q 'axis x: Operation enabled' "$tmp/node.log" || lab_fail "the node never showed Operation enabled"

# 2. The server killed mid-job: quick stop within the watchdog, standstill.
lab_start job-1 rig -- "$netmc" run --server "127.0.0.1:$port" --clock realtime --controller adrc --iterations 1
sleep 3
killed_at=$(date +%s.%N)
lab_kill server
lab_wait job-1 30 || true
for drive in drive-x drive-y; do
  lab_wait_log "$drive" 'Operation enabled -> Quick stop active' 5 || lab_fail "$drive saw no quick stop after the server died"
  line=$(grep -m1 'Operation enabled -> Quick stop active' "$tmp/$drive.log")
  stopped=$(date -d "$(echo "$line" | cut -c1-23)" +%s.%N)
  awk -v a="$killed_at" -v b="$stopped" -v d="$drive" 'BEGIN {
    ms = (b - a) * 1e3; printf "server killed: %s quick stop %.0f ms later\n", d, ms; exit (ms <= 250) ? 0 : 1 }' ||
    lab_fail "$drive: the quick stop came later than 250 ms after the server died"
  lab_wait_log "$drive" 'Quick stop active -> Switch on disabled' 5 || lab_fail "$drive did not come to standstill"
done
grep -q 'axis x: Quick stop active' "$tmp/node.log" && grep -q 'axis x: Switch on disabled' "$tmp/node.log" ||
  lab_fail "the node did not report Quick stop active, then Switch on disabled"
echo "node reported: $(grep -o 'axis x: \(Quick stop active\|Switch on disabled\)' "$tmp/node.log" | tail -n 2 | paste -sd' ' -)"
server server-2

# 3. A trip at the window's edge ends in Fault; the operator's reset brings the axis back.
lab_stop node
node node-2 x=0.045:0.065,y=0:0.12
status=0
run --controller adrc --iterations 1 >"$tmp/trip.txt" 2>&1 || status=$?
[ "$status" -ne 0 ] && grep -q 'axis x tripped: position .* outside the window \[0.045, 0.065\] m' "$tmp/trip.txt" ||
  lab_fail "the job that leaves x's window did not fail naming the trip: $(cat "$tmp/trip.txt")"
for _ in $(seq 30); do
  lab_exec rig -- "$netmc" nodes --server "127.0.0.1:$port" --json >"$tmp/nodes.json"
  grep -q '"state": "Fault"' "$tmp/nodes.json" && break
  sleep 0.1
done
grep -q '"state": "Fault"' "$tmp/nodes.json" || lab_fail "netmc nodes does not show axis x in Fault: $(cat "$tmp/nodes.json")"
echo "window trip: $(grep -o 'axis x tripped: [^;]*' "$tmp/trip.txt" | head -n 1); netmc nodes: Fault"
! lab_exec rig -- "$netmc" reset rig --server "127.0.0.1:$port" >/dev/null 2>"$tmp/reset.err" ||
  lab_fail "a reset without the admin token was taken"
grep -q 'needs the admin token' "$tmp/reset.err" || lab_fail "the refused reset does not say why: $(cat "$tmp/reset.err")"
lab_exec rig -- env NETMC_TOKEN_FILE="$tmp/admin.token" "$netmc" reset rig --server "127.0.0.1:$port" >"$tmp/reset.txt"
run "${small[@]}" --quiet >/dev/null || lab_fail "the job after the reset failed"
grep 'axis x ' "$tmp/reset.txt" | grep -q 'Switch on disabled' || lab_fail "after the reset axis x is not in Switch on disabled: $(cat "$tmp/reset.txt")"
echo "netmc reset (admin token): axis x Switch on disabled; the next job ran"

# 4. The emulator killed mid-job: a trip naming the lost connection; back, reset, the next job.
lab_start job-2 rig -- "$netmc" run --server "127.0.0.1:$port" --clock realtime "${small[@]}"
sleep 2
lab_kill drive-x
status=0
lab_wait job-2 30 || status=$?
[ "$status" -ne 0 ] && grep -q 'axis x tripped: .*(registers .*\(connection closed\|timeout\|not connected\)' "$tmp/job-2.log" ||
  lab_fail "the job on a dead drive did not fail naming the cause: $(cat "$tmp/job-2.log")"
echo "emulator killed: $(grep -o 'axis x tripped: [^;]*' "$tmp/job-2.log" | head -n 1)"
emulate drive-x-2 0 0.05 "$px"
lab_wait_log drive-x-2 'master .* connected' 5 || lab_fail "the node did not reconnect to the restarted drive"
lab_exec rig -- env NETMC_TOKEN_FILE="$tmp/admin.token" "$netmc" reset rig --server "127.0.0.1:$port" >/dev/null
run "${small[@]}" --quiet >/dev/null || lab_fail "the job after the emulator's restart failed"
echo "restarted and reset: the next job ran"

# 5. Modbus exceptions from the drive: a trip naming the exception and the register.
lab_stop drive-x-2
emulate drive-x-3 0 0.05 "$px" --fail-after 2s:exception
lab_wait_log drive-x-3 'master .* connected' 5 || lab_fail "the node did not reconnect to the restarted drive"
lab_exec rig -- env NETMC_TOKEN_FILE="$tmp/admin.token" "$netmc" reset rig --server "127.0.0.1:$port" >/dev/null
status=0
run "${small[@]}" >"$tmp/exception.txt" 2>&1 || status=$?
[ "$status" -ne 0 ] && grep -q 'axis x tripped: .*registers .*Modbus exception 4 (server device failure)' "$tmp/exception.txt" ||
  lab_fail "Modbus exceptions did not trip the axis naming them: $(cat "$tmp/exception.txt")"
echo "Modbus exceptions: $(grep -o 'axis x tripped: [^;]*' "$tmp/exception.txt" | head -n 1)"
for name in node-2 server-2 drive-x-3 drive-y; do
  [ "$(lab_status "$name")" = running ] || lab_fail "$name ended: nothing may crash"
done
