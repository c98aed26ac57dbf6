#!/usr/bin/env bash
# A single-axis tracking job over DDS (thesis ch. 5): netmc-server and one netmc-axis process on
# loopback hosting axis x with the dead-zone plant (hiwin), lockstep over UDP. The thesis's Table
# 5-1 study (`--preset thesis-dead-zone`: C1-C5, the dead zone estimated or inverted), shortened to
# 1 s per run, must give the same JSON, byte for byte, as `netmc sim` in-process: metrics and the
# controllers' final estimates.
# Usage: single_axis_lockstep.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
shift

start x "$netmc_axis" --node it-x --axes x --plant hiwin --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
port=$(server_port 127.0.0.1)

SECONDS=0
"$netmc" run --server "127.0.0.1:$port" --quiet --preset thesis-dead-zone --duration 1s \
  --json "$tmp/dds.json" >"$tmp/dds.txt"
wall=$SECONDS
"$netmc" sim --preset thesis-dead-zone --duration 1s --json "$tmp/sim.json" >"$tmp/sim.txt"
# One axis, and the estimates of C3 (six parameters and d_c) in the results.
axes=$(awk '/"tracking_rms_m": \[/ {inside = 1; next} inside && /\]/ {print n; exit} inside {n++}' "$tmp/sim.json")
[ "$axes" = 1 ] || { echo "FAIL: expected metrics of 1 axis, got $axes"; exit 1; }
grep -q '"name": "mlbl_hat"' "$tmp/dds.json" || { echo "FAIL: no dead-zone estimates in the DDS run's JSON"; exit 1; }
same_json "$tmp/sim.json" "$tmp/dds.json" "one axis in lockstep over DDS ($wall s)"
grep -E "netmc-server: job [0-9]+ running on axes x " "$tmp/server.log" | head -1
