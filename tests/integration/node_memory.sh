#!/usr/bin/env bash
# A realtime axis node's memory for the longest iteration a job may have (10^7 cycles: 10 000 s
# at 1 kHz): what the node keeps per iteration is bounded (round-trip and wake-up statistics
# binned from the start, the newest 4096 feedback send times), not 8 bytes a cycle per record
# (before: 80 MB of send times written when the iteration started, two records growing). Each node's RSS is sampled for 20 s into such an iteration
# and must stay within 16 MiB of what it was after a short job (docs/operations/memory-bounds.md).
# The job is cancelled and the next short job completes.
# Usage: node_memory.sh BUILD_DIR   (loopback only)
source "$(dirname "$0")/lib.sh" "$@"
rss_kib() { awk '/^VmRSS/ { print $2 }' "/proc/$1/status"; }
head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/token"
export NETMC_TOKEN_FILE=$tmp/token  # the admin's: cancels the job it did not submit on this connection

node_pids=()
for axis in x y; do
  start "$axis" "$netmc_axis" --node mem-$axis --axes $axis --clock realtime --domain "$domain" \
    --transport udp
  node_pids+=("${pids[-1]}")
done
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --admin-token-file "$tmp/token"
port=$(server_port 127.0.0.1)
server=(--server "127.0.0.1:$port")
short=(--quiet --clock realtime --controller adrc --iterations 1 --duration 0.5s)

"$netmc" run "${server[@]}" "${short[@]}" >/dev/null
before=()
for pid in "${node_pids[@]}"; do before+=("$(rss_kib "$pid")"); done

long=$("$netmc" submit "${server[@]}" --quiet --clock realtime --controller adrc --iterations 1 \
  --sample-period 1ms --duration 10000s)
for _ in $(seq 100); do "$netmc" status "$long" "${server[@]}" | grep -q running && break; sleep 0.1; done
"$netmc" status "$long" "${server[@]}" | grep -q running || { echo "FAIL: the long job did not start"; exit 1; }
peak=(0 0)
for _ in $(seq 40); do
  sleep 0.5
  for i in 0 1; do
    now=$(rss_kib "${node_pids[$i]}")
    [ "$now" -gt "${peak[$i]}" ] && peak[$i]=$now
  done
done
"$netmc" status "$long" "${server[@]}" | grep -q running || { echo "FAIL: the long job ended early:"; \
  "$netmc" status "$long" "${server[@]}"; exit 1; }
"$netmc" cancel "$long" "${server[@]}" >/dev/null
for i in 0 1; do
  grown=$(( peak[i] - before[i] ))
  echo "node mem-$([ "$i" = 0 ] && echo x || echo y): RSS after a short job ${before[$i]} KiB; 20 s into an iteration of 10^7 cycles at most ${peak[$i]} KiB (+$grown KiB)"
  [ "$grown" -le $((16 * 1024)) ] || { echo "FAIL: the node grew by $grown KiB (bound 16384)"; exit 1; }
done
for _ in $(seq 100); do "$netmc" status "$long" "${server[@]}" | grep -q cancelled && break; sleep 0.1; done
"$netmc" run "${server[@]}" "${short[@]}" --json "$tmp/after.json" >/dev/null  # fails unless done
/usr/bin/python3 -c 'import json, sys; assert len(json.load(open(sys.argv[1]))["runs"][0]["iterations"]) == 1' \
  "$tmp/after.json" || { echo "FAIL: the job after the long one has no iteration"; exit 1; }
echo "node memory: bounded for the longest iteration; the next job done"
