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
# A study of one job: netmc watch of it (job 1 of this fresh server) prints netmc run's table
# (the title line aside: run names the study, watch the job) and writes its JSON.
if [ "$(grep -c '"label":' "$tmp/dds.json")" -eq 1 ]; then
  "$netmc" watch 1 --server "127.0.0.1:$port" --quiet --json "$tmp/watch.json" >"$tmp/watch.txt"
  diff <(tail -n +2 "$tmp/dds.txt") <(tail -n +2 "$tmp/watch.txt") ||
    { echo "FAIL: netmc watch prints another table than netmc run"; exit 1; }
  same_json "$tmp/dds.json" "$tmp/watch.json" "netmc watch --json"
  echo "netmc watch 1: netmc run's table ($(wc -l <"$tmp/watch.txt") lines)"
fi
