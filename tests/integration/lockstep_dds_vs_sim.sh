#!/usr/bin/env bash
# netmc-server and two netmc-axis processes (one per axis) on loopback, lockstep over DDS/UDP:
# the paper-001 preset must give the same JSON, byte for byte, as `netmc sim` in-process.
# Usage: [DDS_ARGS="..."] lockstep_dds_vs_sim.sh BUILD_DIR [extra study flags...]
# DDS_ARGS replaces the DDS transport flags of the server and axes (default: --transport udp).
set -euo pipefail
trap 'echo "$0: failed at line $LINENO (exit $?)"' ERR
build=$1
shift
source "$(dirname "$0")/lib.sh"
read -r -a dds_args <<<"${DDS_ARGS:---transport udp}"

start x "$build/server/axis/netmc-axis" --node it-x --axes x --domain "$domain" "${dds_args[@]}"
start y "$build/server/axis/netmc-axis" --node it-y --axes y --domain "$domain" "${dds_args[@]}"
start server "$build/server/service/netmc-server" --listen 127.0.0.1:0 --domain "$domain" "${dds_args[@]}"
port=$(server_port 127.0.0.1)

"$build/client/netmc" run --server "127.0.0.1:$port" --quiet --json "$tmp/dds.json" "$@" >"$tmp/dds.txt"
"$build/client/netmc" sim --json "$tmp/sim.json" "$@" >"$tmp/sim.txt"
cat "$tmp/dds.txt"
same_json "$tmp/sim.json" "$tmp/dds.json" "lockstep over DDS"
