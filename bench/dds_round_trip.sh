#!/usr/bin/env bash
# Feedback-to-setpoint round trip of the closed loop over DDS (realtime, h = 1 ms, no netsim
# delay, UDP loopback, two axis processes) beside a bare Fast DDS ping-pong of the same samples
# at the same rate, measured in the same run. Usage: bench/dds_round_trip.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
tmp=$(mktemp -d)
domain=$(( 100 + RANDOM % 100 ))
pids=()
cleanup() { for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done; wait 2>/dev/null || true; rm -rf "$tmp"; }
trap cleanup EXIT

"$build/bench/netmc_dds_ping_pong" --role pong --domain "$domain" --seconds 30 &
pids+=($!)
"$build/bench/netmc_dds_ping_pong" --role ping --domain "$domain" --rate 1000 --count 5000

domain=$((domain + 1))
for axis in x y; do
  "$build/server/axis/netmc-axis" --node bench-$axis --axes $axis --clock realtime --domain "$domain" \
    --transport udp >/dev/null 2>&1 &
  pids+=($!)
done
"$build/server/service/netmc-server" --listen 127.0.0.1:0 --domain "$domain" --transport udp >"$tmp/server.log" 2>&1 &
pids+=($!)
port=""
for _ in $(seq 100); do
  port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/server.log"); [ -n "$port" ] && break; sleep 0.1
done
"$build/client/netmc" run --server "127.0.0.1:$port" --quiet --clock realtime --controller adrc \
  --sample-period 1ms --duration 5s --iterations 1 --delay none --json "$tmp/loop.json" >/dev/null
p50=$(sed -n 's/.*"tau_p50_s": \([0-9.eE+-]*\).*/\1/p' "$tmp/loop.json")
p99=$(sed -n 's/.*"tau_p99_s": \([0-9.eE+-]*\).*/\1/p' "$tmp/loop.json")
max=$(sed -n 's/.*"tau_max_s": \([0-9.eE+-]*\).*/\1/p' "$tmp/loop.json")
awk -v a="$p50" -v b="$p99" -v c="$max" 'BEGIN { printf "closed loop over DDS at 1000 Hz (2 axis processes): feedback-to-setpoint p50 %.0f us, p99 %.0f us, max %.0f us\n", a*1e6, b*1e6, c*1e6 }'
