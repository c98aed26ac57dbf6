#!/usr/bin/env bash
# A three-axis contour over DDS: netmc-server and two netmc-axis processes on loopback, one
# hosting x and y, the other z (linear-motor plants), lockstep over UDP. The thesis's ch. 6 study
# (`--preset thesis-spatial`, GTCF-SARC on a tilted circle in space under six loop delays, 4 s per
# run: metrics over 3.14-4 s) must
# give the same JSON, byte for byte, as `netmc sim` in-process. The thesis simulates these runs
# unsaturated: their first cycles command up to 27 V, beyond the stage's +-10 V that the nodes'
# simulated drives take by default, so the nodes are told --command-limit 40.
# Usage: three_axis_lockstep.sh BUILD_DIR [extra study flags...]
source "$(dirname "$0")/lib.sh" "$@"
shift

start xy "$netmc_axis" --node it-xy --axes x,y --plant linmotor --command-limit 40 \
  --domain "$domain" --transport udp
start z "$netmc_axis" --node it-z --axes z --plant linmotor --command-limit 40 \
  --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
port=$(server_port 127.0.0.1)

SECONDS=0
"$netmc" run --server "127.0.0.1:$port" --quiet --preset thesis-spatial --duration 4s --json "$tmp/dds.json" "$@" >"$tmp/dds.txt"
wall=$SECONDS
"$netmc" sim --preset thesis-spatial --duration 4s --json "$tmp/sim.json" "$@" >"$tmp/sim.txt"
cat "$tmp/dds.txt"
# Per-axis metrics of the first run: one value per axis.
axes=$(awk '/"tracking_rms_m": \[/ {inside = 1; next} inside && /\]/ {print n; exit} inside {n++}' "$tmp/sim.json")
[ "$axes" = 3 ] || { echo "FAIL: expected metrics of 3 axes, got $axes"; exit 1; }
same_json "$tmp/sim.json" "$tmp/dds.json" "three axes in lockstep over DDS ($wall s)"
grep -E "netmc-server: job [0-9]+ running on axes x,y,z " "$tmp/server.log" | head -1
