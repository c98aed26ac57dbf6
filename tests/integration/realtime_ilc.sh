#!/usr/bin/env bash
# Realtime mode at h = 5 ms over DDS/UDP on loopback with uniform 0.3-0.8 ms netsim delay on
# the downlink: ADRC+ILCCC must still cut e_sum by at least 80 % from its first iteration (plain
# ADRC) within 5 iterations. Prints the measured loop-delay statistics.
# Usage: realtime_ilc.sh BUILD_DIR
set -euo pipefail
trap 'echo "$0: failed at line $LINENO (exit $?)"' ERR
build=$1
tmp=$(mktemp -d)
domain=$(( 100 + RANDOM % 100 ))
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT

for axis in x y; do
  "$build/server/axis/netmc-axis" --node rt-$axis --axes $axis --clock realtime --domain "$domain" \
    --transport udp >"$tmp/$axis.log" 2>&1 &
  pids+=($!)
done
"$build/server/service/netmc-server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  >"$tmp/server.log" 2>&1 &
pids+=($!)
port=""
for _ in $(seq 100); do
  port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/server.log")
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { echo "netmc-server did not start"; cat "$tmp/server.log"; exit 1; }

"$build/client/netmc" run --server "127.0.0.1:$port" --clock realtime --controller adrc+ilccc \
  --iterations 5 --curve --json "$tmp/rt.json"
sums=$(sed -n 's/.*"e_sum_m": \([0-9.eE+-]*\).*/\1/p' "$tmp/rt.json")
first=$(echo "$sums" | head -n 1)
last=$(echo "$sums" | tail -n 1)
awk -v first="$first" -v last="$last" 'BEGIN {
  cut = 1 - last / first
  printf "realtime: e_sum %.3f mm (iteration 1, ADRC) -> %.3f mm (iteration 5): cut %.1f %%\n", first * 1e3, last * 1e3, cut * 100
  exit (cut >= 0.80) ? 0 : 1
}'
