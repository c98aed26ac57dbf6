#!/usr/bin/env bash
# netmc-server and two netmc-axis processes (one per axis) on loopback, lockstep over DDS/UDP:
# the paper-001 preset must give the same JSON, byte for byte, as `netmc sim` in-process.
# Usage: [DDS_ARGS="..."] lockstep_dds_vs_sim.sh BUILD_DIR [extra study flags...]
# DDS_ARGS replaces the DDS transport flags of the server and axes (default: --transport udp).
source "$(dirname "$0")/lib.sh" "$@"
shift
read -r -a dds_args <<<"${DDS_ARGS:---transport udp}"

start x "$netmc_axis" --node it-x --axes x --domain "$domain" "${dds_args[@]}"
start y "$netmc_axis" --node it-y --axes y --domain "$domain" "${dds_args[@]}"
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" "${dds_args[@]}"
port=$(server_port 127.0.0.1)

"$netmc" run --server "127.0.0.1:$port" --quiet --json "$tmp/dds.json" "$@" >"$tmp/dds.txt"
"$netmc" sim --json "$tmp/sim.json" "$@" >"$tmp/sim.txt"
cat "$tmp/dds.txt"
same_json "$tmp/sim.json" "$tmp/dds.json" "lockstep over DDS"
