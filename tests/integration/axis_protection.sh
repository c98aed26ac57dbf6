#!/usr/bin/env bash
# An axis that protects itself, on loopback in lockstep: one node hosts x and y, with a travel
# window of its own per axis, x [-1, 55] mm and y [30, 70] mm. Paper 001's circle (x and y from
# 40 to 60 mm) leaves x's window and stays in y's:
#   - the job fails at once with the axis's reason, and the node's status shows the fault;
#   - the fault latches: the next job is refused, naming it;
#   - the operator resets it on the axis's host (SIGUSR1); a job inside the window then runs.
# Usage: axis_protection.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"

start x "$netmc_axis" --node guard --axes x,y --position-window x=-0.001:0.055,y=0.03:0.07 \
  --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
port=$(server_port 127.0.0.1)
for _ in $(seq 50); do grep -q "limits x:" "$tmp/x.log" && break; sleep 0.1; done
grep -q "limits x: command 1, position \[-0.001, 0.055\] m; y: command 1, position \[0.03, 0.07\] m," "$tmp/x.log" ||
  { echo "FAIL: the node does not state each axis's limits"; cat "$tmp/x.log"; exit 1; }
echo "node guard: $(sed -n 's/.*\(limits x: .*\), clock .*/\1/p' "$tmp/x.log")"

first=0
"$netmc" run --server "127.0.0.1:$port" --quiet --controller adrc --iterations 1 >"$tmp/first.txt" 2>&1 || first=$?
[ "$first" -ne 0 ] || { echo "FAIL: the job that leaves the window succeeded"; exit 1; }
grep -q "axis x tripped: position .* outside the window \[-0.001, 0.055\] m" "$tmp/first.txt" ||
  { echo "FAIL: the failure does not name the axis and its reason:"; cat "$tmp/first.txt"; exit 1; }
! grep -q "axis y tripped" "$tmp/first.txt" "$tmp/x.log" || { echo "FAIL: y tripped inside its own window"; exit 1; }
echo "job 1 failed: $(grep -o 'axis x tripped: [^;]*' "$tmp/first.txt" | head -1)"
grep -q "FAULT" "$tmp/x.log"
# The node reports the fault on its status (netmc nodes).
for _ in $(seq 40); do
  "$netmc" nodes --server "127.0.0.1:$port" >"$tmp/nodes.txt"
  grep -q "^guard .*fault" "$tmp/nodes.txt" && break
  sleep 0.1
done
grep "^guard " "$tmp/nodes.txt"
grep -q "^guard .*fault" "$tmp/nodes.txt" || { echo "FAIL: the node's status does not show the fault"; exit 1; }

second=0
"$netmc" run --server "127.0.0.1:$port" --quiet --controller adrc --iterations 1 \
  --trajectory circle:r=2mm,cx=50mm,cy=50mm,period=8s >"$tmp/second.txt" 2>&1 || second=$?
[ "$second" -ne 0 ] && grep -q "axis x is in fault" "$tmp/second.txt" ||
  { echo "FAIL: a job on the faulted axis was not refused:"; cat "$tmp/second.txt"; exit 1; }
echo "job 2 refused: the fault latched"

kill -USR1 "${pids[0]}"
for _ in $(seq 40); do grep -q "faults of axes x reset by the operator" "$tmp/x.log" && break; sleep 0.05; done
grep -q "faults of axes x reset by the operator" "$tmp/x.log"
sleep 1  # the reset status reaches the server
"$netmc" run --server "127.0.0.1:$port" --quiet --controller adrc --iterations 1 \
  --trajectory circle:r=2mm,cx=50mm,cy=50mm,period=8s --json "$tmp/third.json" >/dev/null
echo "after the operator's reset (SIGUSR1), a job inside the window runs"
