#!/usr/bin/env bash
# DDS Security on loopback (scripts/make-lab-pki.sh; Fast DDS's PKI-DH, access control, AES-GCM):
#   - the paper-001 lockstep job through authenticated, encrypted DDS equals `netmc sim`;
#   - a participant without a certificate of the lab's CA receives no sample (an iteration-log
#     listener hears nothing) and moves no axis (a server without one finds no node);
#   - a participant with a valid certificate but no permission to write setpoints cannot: a
#     server started under the monitor's identity cannot create its writers;
#   - the monitor, allowed to read iteration logs, reads them;
#   - a node with a valid certificate cannot host (write the feedback of) another node's axis.
# Usage: dds_security.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
pki=$tmp/pki
bash "$(dirname "$0")/../../scripts/make-lab-pki.sh" "$pki" --server netmc-server --node sec-x:x --node sec-y:y \
  --reader monitor >/dev/null
secure=(--security "$pki" --domain "$domain" --transport udp)
listener=$build/tests/integration/netmc_iteration_log_listener

start x "$netmc_axis" --node sec-x --axes x "${secure[@]}"
start y "$netmc_axis" --node sec-y --axes y "${secure[@]}"
start server "$netmc_server" --listen 127.0.0.1:0 "${secure[@]}"
port=$(server_port 127.0.0.1)
grep -q "DDS Security as netmc-server" "$tmp/server.log"
start monitor "$listener" --domain "$domain" --security "$pki" --name monitor --seconds 120
start outsider "$listener" --domain "$domain" --seconds 120
sleep 1

study=(--controller adrc,adrc+ilccc --iterations 3)
"$netmc" run --server "127.0.0.1:$port" --quiet --json "$tmp/dds.json" "${study[@]}" >/dev/null
"$netmc" sim --json "$tmp/sim.json" "${study[@]}" >/dev/null
same_json "$tmp/sim.json" "$tmp/dds.json" "lockstep over authenticated, encrypted DDS"
sleep 1
logs_monitor=$(grep -c '^[0-9a-f]* [0-9]* ' "$tmp/monitor.log" || true)
logs_outsider=$(grep -c '^[0-9a-f]* [0-9]* ' "$tmp/outsider.log" || true)
echo "iteration logs: the monitor (certificate, read permission) got $logs_monitor, the outsider (none) $logs_outsider"
[ "$logs_monitor" -eq 6 ] || { echo "FAIL: the monitor should read all 6 iteration logs"; exit 1; }
[ "$logs_outsider" -eq 0 ] || { echo "FAIL: a participant without a certificate read iteration logs"; exit 1; }

# A server without a certificate: the secure nodes are invisible to it.
start rogue "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --discovery-timeout 3000 --dds-name rogue-server
for _ in $(seq 100); do grep -q "listening on" "$tmp/rogue.log" && break; sleep 0.1; done
rogue_port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/rogue.log")
rogue_exit=0
"$netmc" run --server "127.0.0.1:$rogue_port" --quiet --controller adrc --iterations 1 \
  >"$tmp/rogue_run.txt" 2>&1 || rogue_exit=$?
[ "$rogue_exit" -ne 0 ] && grep -q "no axis node for axis x was discovered" "$tmp/rogue_run.txt" ||
  { echo "FAIL: a server without a certificate reached the axes:"; cat "$tmp/rogue_run.txt"; exit 1; }
echo "a server without a certificate: $(grep -o 'no axis node for axis x was discovered[^"]*' "$tmp/rogue_run.txt" | head -1)"

# A valid certificate without the right to write setpoints (the monitor's) cannot serve as a server.
monitor_exit=0
timeout 30 "$netmc_server" --listen 127.0.0.1:0 "${secure[@]}" --dds-name monitor \
  >"$tmp/impostor.log" 2>&1 || monitor_exit=$?
[ "$monitor_exit" -ne 0 ] && [ "$monitor_exit" -ne 124 ] ||
  { echo "FAIL: the monitor's identity ran a server (exit $monitor_exit):"; cat "$tmp/impostor.log"; exit 1; }
echo "the monitor's certificate as a server: exit $monitor_exit, $(grep -m1 'error' "$tmp/impostor.log")"

# A node's certificate covers its own axes' partitions only: sec-y cannot stand in for axis x.
impostor_exit=0
timeout 30 "$netmc_axis" --node sec-y --axes x "${secure[@]}" >"$tmp/axis_impostor.log" 2>&1 ||
  impostor_exit=$?
[ "$impostor_exit" -ne 0 ] && [ "$impostor_exit" -ne 124 ] ||
  { echo "FAIL: node sec-y served axis x (exit $impostor_exit)"; cat "$tmp/axis_impostor.log"; exit 1; }
echo "node sec-y as axis x: exit $impostor_exit, $(grep -m1 'error' "$tmp/axis_impostor.log")"
