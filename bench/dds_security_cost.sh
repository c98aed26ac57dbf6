#!/usr/bin/env bash
# What DDS Security costs the realtime loop: paper 001's job (adrc+ilccc, circle, no netsim
# delay) at h = 1 ms for 10 s on loopback UDP, once in the clear and once with authentication,
# access control and AES-GCM encryption of every topic (scripts/make-lab-pki.sh), alternately
# RUNS times each. Prints tau (setpoint arrival - sample time) and the deadline misses of every
# run. Measured, never asserted. Usage: bench/dds_security_cost.sh BUILD_DIR [RUNS]
source "$(dirname "$0")/../tests/integration/lib.sh" "$@"
runs=${2:-3}
pki=$tmp/pki
bash "$(dirname "$0")/../scripts/make-lab-pki.sh" "$pki" --server netmc-server --node cost-x:x --node cost-y:y >/dev/null

one_run() {  # one_run LABEL [--security DIR]: prints LABEL and the run's tau line
  local label=$1
  shift
  local before=${#pids[@]}
  start "x-$label" "$netmc_axis" --node cost-x --axes x --clock realtime --domain "$domain" \
    --transport udp "$@"
  start "y-$label" "$netmc_axis" --node cost-y --axes y --clock realtime --domain "$domain" \
    --transport udp "$@"
  start "server-$label" "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp "$@"
  local port=""
  for _ in $(seq 100); do
    port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/server-$label.log")
    [ -n "$port" ] && break
    sleep 0.1
  done
  local out
  out=$("$netmc" run --server "127.0.0.1:$port" --clock realtime --sample-period 1ms --duration 10s \
    --controller adrc+ilccc --iterations 1 --delay none 2>&1)
  echo "$label: $(grep -o -m1 'tau mean/p99/max [0-9./]* ms' <<<"$out" | head -1), $(grep -o -m1 'deadline misses [0-9]*' <<<"$out" | head -1) of 10001"
  # Stop this run's processes before the next one starts.
  local pid
  for pid in "${pids[@]:$before}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]:$before}"; do while kill -0 "$pid" 2>/dev/null; do sleep 0.1; done; done
  domain=$((domain + 1))
}

for run in $(seq "$runs"); do
  one_run "clear-$run"
  one_run "secure-$run" --security "$pki"
done
