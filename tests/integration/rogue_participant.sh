#!/usr/bin/env bash
# A rogue DDS participant (tests/integration/rogue_participant.cpp) on the domain of a netmc
# server and its axis nodes, without DDS Security (which keeps it out altogether:
# integration.dds_security), on loopback:
#   1. drive: as a server of its own it starts a job on an idle lockstep axis whose node obeys any
#      server (--any-server; its simulated drive's rated input is its command limit) and commands
#      1e30: the axis trips at the first command (position stays 0), says so, and stays up; NaN
#      commands to a realtime axis: the same. An axis whose node has default flags obeys only
#      netmc-server (--server-name's default) and ignores the rogue altogether: no sample, no
#      event, and the node says whom it ignored.
#   2. hijack, lockstep (nodes with default flags): while paper 001's adrc+ilccc job runs (2
#      iterations), it speaks in the server's and the node's names: setpoints with sequence number
#      2^64-2 and NaN commands for the next cycle, feedback 5 mm off, faults, END_JOB, and node
#      statuses spoofing the node.
#      The job's JSON equals netmc sim's byte for byte; node and server log the forgeries.
#   3. hijack, realtime (1 ms, 1 s; nodes with --any-server: what is tested is the check of each
#      sample's sender, not of the rogue's name): the job completes with no stale setpoint and an
#      e_max within 0.67-1.5 times netmc sim's (a loaded 2-core machine stretches the real delays).
# Usage: rogue_participant.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
axis_bin=$netmc_axis
rogue=$build/tests/integration/netmc_rogue_participant
dds=(--domain "$domain" --transport udp)

start gz "$axis_bin" --node guard-z --axes z --any-server "${dds[@]}"
start gw "$axis_bin" --node guard-w --axes w --command-limit 50 --clock realtime --any-server "${dds[@]}"
start hx "$axis_bin" --node hx --axes x "${dds[@]}"
start hy "$axis_bin" --node hy --axes y "${dds[@]}"
start rx "$axis_bin" --node rx --axes rx --clock realtime --any-server "${dds[@]}"
start ry "$axis_bin" --node ry --axes ry --clock realtime --any-server "${dds[@]}"
start server "$netmc_server" --listen 127.0.0.1:0 "${dds[@]}"
port=$(server_port 127.0.0.1)
for node in gz gw hx hy rx ry; do
  for _ in $(seq 100); do grep -q serving "$tmp/$node.log" && break; sleep 0.1; done
done

# 1. A job of the rogue's own on idle axes with operator limits.
"$rogue" drive --axis z --command 1e30 --seconds 10 --domain "$domain" | tee "$tmp/drive-z.txt"
grep -q "event AXIS_FAULT: axis z tripped: command 1e+30" "$tmp/drive-z.txt" ||
  { echo "FAIL: axis z did not trip on a command of 1e30"; cat "$tmp/gz.log"; exit 1; }
grep -q "largest |position| 0 m" "$tmp/drive-z.txt" || { echo "FAIL: axis z moved"; exit 1; }
grep -q "axis z FAULT (job 4242): command 1e+30 (cycle 0) beyond the axis's limit 1;" "$tmp/gz.log" ||
  { echo "FAIL: the default limit (seed001's rated input, 1) did not trip axis z"; cat "$tmp/gz.log"; exit 1; }
"$rogue" drive --axis x --command 0.5 --seconds 2 --domain "$domain" | tee "$tmp/drive-x.txt"
grep -q "0 samples back, largest |position| 0 m, event none" "$tmp/drive-x.txt" &&
  grep -q "is ignored: this node obeys server 'netmc-server' only" "$tmp/hx.log" ||
  { echo "FAIL: a node with default flags obeyed the rogue"; cat "$tmp/hx.log"; exit 1; }
echo "default flags: $(grep -o "participant [0-9a-f]* ('rogue') is ignored[^)]*)" "$tmp/hx.log" | head -n 1)"
"$rogue" drive --axis w --clock realtime --nan --seconds 10 --domain "$domain" | tee "$tmp/drive-w.txt"
grep -q "event AXIS_FAULT: axis w tripped: .*not finite" "$tmp/drive-w.txt" ||
  { echo "FAIL: axis w did not trip on a NaN command"; cat "$tmp/gw.log"; exit 1; }
grep -q "largest |position| 0 m" "$tmp/drive-w.txt" || { echo "FAIL: axis w moved"; exit 1; }
kill -0 "${pids[0]}" && kill -0 "${pids[1]}" || { echo "FAIL: an attacked node died"; exit 1; }
echo "idle axes driven by a rogue server: both tripped at the first command, did not move, and are up"
# The server counts each trip from the nodes' reports (netmc nodes --json; /metrics' netmc_axis_trips_total).
for _ in $(seq 50); do
  "$netmc" nodes --server "127.0.0.1:$port" --json >"$tmp/nodes.json"
  python3 - "$tmp/nodes.json" <<'PY' && break
import json, sys
drives = {d["axis"]: d for n in json.load(open(sys.argv[1]))["nodes"] for d in n.get("drives", [])}
sys.exit(0 if all(int(drives.get(a, {}).get("trips", 0)) == 1 for a in ("z", "w")) else 1)
PY
  sleep 0.1
done
python3 - "$tmp/nodes.json" <<'PY' || { echo "FAIL: the server did not count one trip each of z and w"; cat "$tmp/nodes.json"; exit 1; }
import json, sys
drives = {d["axis"]: d for n in json.load(open(sys.argv[1]))["nodes"] for d in n.get("drives", [])}
assert all(int(drives[a]["trips"]) == 1 for a in ("z", "w")), {a: drives[a].get("trips") for a in ("z", "w")}
assert int(drives["x"].get("trips", 0)) == 0
PY
echo "the server counted the trips: z 1, w 1, x 0 (netmc nodes --json)"

# 2. Hijack of a lockstep job.
study=(--controller adrc+ilccc --iterations 2)
start rogue-x "$rogue" hijack --axis x --seconds 120 --domain "$domain"
rogue_pid=${pids[-1]}
for _ in $(seq 100); do grep -q "waiting for a job" "$tmp/rogue-x.log" && break; sleep 0.1; done
"$netmc" run --server "127.0.0.1:$port" --quiet "${study[@]}" --json "$tmp/run.json" >/dev/null
# The rogue forges node statuses every 100 ms, alternating two kinds, for as long as it runs; the
# job alone can be shorter than the server's discovery of the rogue's status writer on a loaded
# machine, so the rogue stays until the server has logged both kinds (or 10 s).
for _ in $(seq 100); do
  grep -q "ignored a status of node hx: names participant" "$tmp/server.log" &&
    grep -q "ignored a status of node hx: participant .* claims the name" "$tmp/server.log" && break
  sleep 0.1
done
kill -TERM "$rogue_pid"
wait "$rogue_pid" || true
cat "$tmp/rogue-x.log"
grep -q "attacking" "$tmp/rogue-x.log" || { echo "FAIL: the rogue never saw the job"; exit 1; }
"$netmc" sim --quiet "${study[@]}" --json "$tmp/sim.json" >/dev/null
same_json "$tmp/sim.json" "$tmp/run.json" "the lockstep job under attack"
grep -q "dropped a forged setpoint for axis x" "$tmp/hx.log" && grep -q "dropped a forged job control for axis x" "$tmp/hx.log" ||
  { echo "FAIL: node hx did not log the forgeries"; cat "$tmp/hx.log"; exit 1; }
grep -q "dropped [0-9]* forged feedback or axis events" "$tmp/server.log" &&
  grep -q "ignored a status of node hx: names participant" "$tmp/server.log" &&
  grep -q "ignored a status of node hx: participant .* claims the name" "$tmp/server.log" ||
  { echo "FAIL: the server did not log the forgeries"; cat "$tmp/server.log"; exit 1; }
grep -h "forged\|ignored a status\|rogue-node" "$tmp/hx.log" "$tmp/server.log" | sed 's/^/log: /'
"$netmc" nodes --server "127.0.0.1:$port" | grep -q "^hx " || { echo "FAIL: the spoofed LEAVING removed hx"; exit 1; }

# 3. Hijack of a realtime job.
rt=(--controller adrc --sample-period 1ms --duration 1s --iterations 1 --delay none)
start rogue-rx "$rogue" hijack --axis rx --seconds 120 --domain "$domain"
rogue_pid=${pids[-1]}
for _ in $(seq 100); do grep -q "waiting for a job" "$tmp/rogue-rx.log" && break; sleep 0.1; done
"$netmc" run --server "127.0.0.1:$port" --quiet --clock realtime --axes rx,ry "${rt[@]}" --json "$tmp/rt.json" >/dev/null
kill -TERM "$rogue_pid"
wait "$rogue_pid" || true
cat "$tmp/rogue-rx.log"
grep -q "attacking" "$tmp/rogue-rx.log" || { echo "FAIL: the rogue never saw the realtime job"; exit 1; }
"$netmc" sim --quiet "${rt[@]}" --json "$tmp/rt-sim.json" >/dev/null
value() { sed -n "s/.*\"$1\": \([0-9.eE+-]*\).*/\1/p" "$2" | head -n 1; }
stale=$(value stale_setpoints "$tmp/rt.json")
[ "${stale:-0}" -eq 0 ] || { echo "FAIL: $stale stale setpoints: the forged sequence number took the axis over"; exit 1; }
awk -v run="$(value e_max_m "$tmp/rt.json")" -v sim="$(value e_max_m "$tmp/rt-sim.json")" 'BEGIN {
  printf "realtime job under attack: e_max %.4f mm (netmc sim %.4f mm), no stale setpoint\n", run * 1e3, sim * 1e3
  exit (run <= 1.5 * sim && run >= 0.67 * sim) ? 0 : 1
}'
