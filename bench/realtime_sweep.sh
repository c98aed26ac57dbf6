#!/usr/bin/env bash
# Realtime timing of the closed loop over DDS on this machine: measured here, never asserted.
# UDP on loopback; every process is started and stopped by this script.
#
#   periods   paper 001's job (adrc+ilccc, circle, no netsim delay) on two axes, one node
#             process each, at each sample period: deadline misses, tau p50/p99, e_max against
#             `netmc sim` of the same spec;
#   rtt       the loop's round trip (feedback written -> setpoint in, on the axis) beside a bare
#             Fast DDS ping-pong of the same types and QoS at the same rate, in the same run;
#   axes      N axes at 1 kHz on one server: N/2 two-axis jobs at once, nodes of up to 8 axes:
#             misses and CPU per axis (server and nodes, user + system time);
#   platform  the machine's own wake-up latency, without netmc: cyclictest (Debian rt-tests),
#             SCHED_FIFO 80, one thread per CPU, memory locked, CPU wake-up latency 0.
# Each part runs with each scheduler: normal, fifo (--rt-priority 80: SCHED_FIFO for every
# process, DDS threads included) and fifo+poll (also --cpu-latency 0).
#
# Usage: bench/realtime_sweep.sh BUILD_DIR [--seconds S] [--periods "5 2 1 0.5 0.2"]
#                                [--axis-counts "2 8 16 32"] [--parts "platform periods rtt axes"]
#                                [--scheds "normal fifo fifo+poll"] [--rtt-periods "1 0.2"]
#                                [--layout split|shared]  (periods: x and y in two nodes or one)
set -euo pipefail
build=$(cd "$1" && pwd)
shift
seconds=10
periods="5 2 1 0.5 0.2"
axis_counts="2 8 16 32"
parts="platform periods rtt axes"
rtt_periods="1 0.2"
layout=split
scheds="normal fifo fifo+poll"
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --periods) periods=$2; shift 2 ;;
    --axis-counts) axis_counts=$2; shift 2 ;;
    --parts) parts=$2; shift 2 ;;
    --scheds) scheds=$2; shift 2 ;;
    --rtt-periods) rtt_periods=$2; shift 2 ;;
    --layout) layout=$2; shift 2 ;;
    *) echo "realtime_sweep.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
case "$layout" in split | shared) ;; *) echo "--layout: expected split or shared" >&2; exit 2 ;; esac
[[ $seconds =~ ^[0-9]+$ ]] || { echo "--seconds: expected whole seconds" >&2; exit 2; }
for sched in $scheds; do
  case "$sched" in
    normal | fifo | fifo+poll | fifo+poll+pin | fifo+poll+lock) ;;
    *) echo "--scheds: unknown scheduler $sched (normal, fifo, fifo+poll, fifo+poll+pin, fifo+poll+lock)" >&2; exit 2 ;;
  esac
done

tmp=$(mktemp -d)
pids=()
stop_all() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  pids=()
}
trap 'stop_all; rm -rf "$tmp"' EXIT
domain=$((100 + RANDOM % 50))
job="--controller adrc+ilccc --delay none --iterations 1 --duration ${seconds}s"
hz=$(getconf CLK_TCK)

# First value of a numeric JSON field in a netmc --json file.
field() { sed -n "s/.*\"$2\": \([-0-9.eE+]*\).*/\1/p" "$1" | head -1; }
cpu_ticks() { awk '{ print $14 + $15 }' "/proc/$1/stat"; }
# The schedulers compared: the default one; SCHED_FIFO; SCHED_FIFO with the CPUs kept out of
# halt (PM QoS wake-up latency 0), which is what a virtual machine's vCPUs need; that with the
# server pinned to the last CPU and the nodes to the others (+pin), or with memory locked (+lock).
# sched_flags SCHED ROLE (ROLE: server or node).
sched_flags() {
  local last=$(( $(nproc) - 1 )) flags=""
  case "$1" in
    normal) ;;
    fifo) flags="--rt-priority 80" ;;
    fifo+poll) flags="--rt-priority 80 --cpu-latency 0" ;;
    fifo+poll+pin)
      flags="--rt-priority 80 --cpu-latency 0"
      if [ "$last" -gt 0 ]; then
        [ "$2" = server ] && flags="$flags --cpus $last" || flags="$flags --cpus 0-$((last - 1))"
      fi ;;
    fifo+poll+lock) flags="--rt-priority 80 --cpu-latency 0 --lock-memory" ;;
  esac
  echo "$flags"
}

# start_cluster SCHED NODE_AXES...: one node per argument (comma-separated axes), one server.
start_cluster() {
  local sched=$1
  shift
  domain=$((domain + 1))
  rm -f "$tmp"/node*.log "$tmp/server.log"  # a log of the last cluster would give its port
  local i=0
  for axes in "$@"; do
    "$build/server/axis/netmc-axis" --node "bench$i" --axes "$axes" --clock realtime --domain "$domain" \
      --transport udp $(sched_flags "$sched" node) >"$tmp/node$i.log" 2>&1 &
    pids+=($!)
    i=$((i + 1))
  done
  "$build/server/service/netmc-server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
    $(sched_flags "$sched" server) >"$tmp/server.log" 2>&1 &
  pids+=($!)
  server_pid=$!
  port=""
  for _ in $(seq 100); do
    port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/server.log" 2>/dev/null || true)
    [ -n "$port" ] && break
    sleep 0.1
  done
  [ -n "$port" ] || { echo "netmc-server did not start" >&2; cat "$tmp/server.log" >&2; exit 1; }
}

# section TITLE COLUMN...: a markdown heading and the head of its table.
section() {
  local title=$1 head="|" rule="|"
  shift
  for column in "$@"; do head="$head $column |"; rule="$rule --- |"; done
  printf '## %s\n\n%s\n%s\n' "$title" "$head" "$rule"
}

percent() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", (b > 0 ? 100 * a / b : 0) }'; }
us() { awk -v v="$1" 'BEGIN { printf "%.0f", v * 1e6 }'; }

if [[ " $parts " == *" platform "* ]]; then
  echo "## This machine's wake-up latency: cyclictest -m -S -p 80 -i 1000 -D ${seconds}s (no netmc running)"
  echo
  if command -v cyclictest >/dev/null; then
    echo '```'
    cyclictest -m -S -p 80 -i 1000 -D "${seconds}s" -q 2>&1 | tail -n +2
    echo '```'
  else
    echo "cyclictest not found (Debian package rt-tests)"
  fi
  echo
fi

if [[ " $parts " == *" periods "* ]]; then
  if [ "$layout" = shared ]; then nodes=(x,y); where="x,y in one node process"; else nodes=(x y); where="x, y in two node processes"; fi
  section "Sample period sweep: 2 axes ($where), ${seconds} s, adrc+ilccc, no netsim delay" \
    h scheduler cycles "deadline misses" "tau p50" "tau p99" e_max "e_max of netmc sim" ratio
  for h in $periods; do
    "$build/client/netmc" sim $job --sample-period "${h}ms" --quiet --json "$tmp/sim.json" >/dev/null
    sim_emax=$(field "$tmp/sim.json" e_max_m)
    for sched in $scheds; do
      start_cluster "$sched" "${nodes[@]}"
      if "$build/client/netmc" run --server "127.0.0.1:$port" --clock realtime $job --sample-period "${h}ms" \
        --quiet --json "$tmp/run.json" >"$tmp/run.log" 2>&1; then
        misses=$(field "$tmp/run.json" deadline_misses)
        cycles=$(awk -v s="$seconds" -v h="$h" 'BEGIN { printf "%d", s * 1000 / h + 1 }')
        emax=$(field "$tmp/run.json" e_max_m)
        echo "| $h ms | $sched | $cycles | $misses ($(percent "$misses" "$cycles") %) | $(us "$(field "$tmp/run.json" tau_p50_s)") µs |" \
          "$(us "$(field "$tmp/run.json" tau_p99_s)") µs | $(awk -v v="$emax" 'BEGIN { printf "%.2f", v * 1e6 }') µm |" \
          "$(awk -v v="$sim_emax" 'BEGIN { printf "%.2f", v * 1e6 }') µm | $(awk -v a="$emax" -v b="$sim_emax" 'BEGIN { printf "%.3f", a / b }') |"
      else
        echo "| $h ms | $sched | – | job failed: $(tail -1 "$tmp/run.log" | cut -c1-120) | | | | | |"
        { echo "--- server log:"; tail -5 "$tmp/server.log"; } >&2
      fi
      stop_all
    done
  done
  echo
fi

if [[ " $parts " == *" rtt "* ]]; then
  section "Round trip: closed loop (feedback written -> setpoint in, on the axis) beside a bare Fast DDS ping-pong, same run" \
    h scheduler axes "ping-pong p50" p99 "loop p50" p99 "p50 ratio" "p99 ratio" "loop's deadline misses"
  for h in $rtt_periods; do
    rate=$(awk -v h="$h" 'BEGIN { printf "%d", 1000 / h }')
    count=$((rate * seconds))
    for sched in $scheds; do
      for rtt_nodes in "x,y" "x y"; do
        domain=$((domain + 1))
        "$build/bench/netmc_dds_ping_pong" --role pong --domain "$domain" --seconds $((seconds + 15)) \
          $(sched_flags "$sched" node) &
        pids+=($!)
        "$build/bench/netmc_dds_ping_pong" --role ping --domain "$domain" --rate "$rate" --count "$count" \
          $(sched_flags "$sched" server) >"$tmp/ping.txt"
        stop_all
        read -r pp50 pp99 < <(sed -n 's/.*p50 \([0-9]*\) us, p99 \([0-9]*\) us.*/\1 \2/p' "$tmp/ping.txt")
        # shellcheck disable=SC2086
        start_cluster "$sched" $rtt_nodes
        rm -f "$tmp/run.json"
        "$build/client/netmc" run --server "127.0.0.1:$port" --clock realtime $job --sample-period "${h}ms" \
          --quiet --json "$tmp/run.json" >"$tmp/run.log" 2>&1 || { echo "--- run:"; tail -2 "$tmp/run.log"; tail -3 "$tmp/server.log"; } >&2
        stop_all
        misses=$([ -f "$tmp/run.json" ] && field "$tmp/run.json" deadline_misses || echo "job failed")
        # The axes' own round trips (one line per axis): the median of their p50s and the worst p99.
        read -r lp50 lp99 < <(sed -n 's/.*round trip feedback->setpoint p50 \([0-9]*\) us p99 \([0-9]*\) us.*/\1 \2/p' \
          "$tmp"/node*.log | sort -n | awk '{ p50[NR] = $1; if ($2 > p99) p99 = $2 } END { print p50[int((NR + 1) / 2)], p99 }')
        label=$([ "$rtt_nodes" = "x,y" ] && echo "x,y in one node" || echo "x, y in two nodes")
        echo "| $h ms | $sched | $label | $pp50 µs | $pp99 µs | $lp50 µs | $lp99 µs |" \
          "$(awk -v a="$lp50" -v b="$pp50" 'BEGIN { printf "%.2f", a / b }') | $(awk -v a="$lp99" -v b="$pp99" 'BEGIN { printf "%.2f", a / b }') |" \
          "$misses of $(awk -v s="$seconds" -v h="$h" 'BEGIN { printf "%d", s * 1000 / h + 1 }') |"
        rm -f "$tmp"/node*.log
      done
    done
  done
  echo
fi

if [[ " $parts " == *" axes "* ]]; then
  section "Axes on one server at 1 kHz: two-axis jobs at once, nodes of up to 8 axes, ${seconds} s" \
    axes jobs nodes scheduler cycles "deadline misses" "worst job" "CPU per axis (server + nodes)"
  for n in $axis_counts; do
    nodes=()
    for ((first = 0; first < n; first += 8)); do
      list=""
      for ((a = first; a < first + 8 && a < n; ++a)); do list="$list${list:+,}a$a"; done
      nodes+=("$list")
    done
    for sched in $scheds; do
      start_cluster "$sched" "${nodes[@]}"
      sleep 1
      before=0
      for pid in "${pids[@]}"; do before=$((before + $(cpu_ticks "$pid"))); done
      started=$(date +%s%N)
      runs=()
      for ((j = 0; j < n / 2; ++j)); do
        "$build/client/netmc" run --server "127.0.0.1:$port" --clock realtime $job --sample-period 1ms \
          --axes "a$((2 * j)),a$((2 * j + 1))" --quiet --json "$tmp/job$j.json" >"$tmp/job$j.log" 2>&1 &
        runs+=($!)
      done
      failed=0
      for pid in "${runs[@]}"; do wait "$pid" || failed=$((failed + 1)); done
      wall_ns=$(( $(date +%s%N) - started ))
      after=0
      for pid in "${pids[@]}"; do after=$((after + $(cpu_ticks "$pid"))); done
      stop_all
      misses=0
      worst=0
      for ((j = 0; j < n / 2; ++j)); do
        m=$(field "$tmp/job$j.json" deadline_misses 2>/dev/null || echo 0)
        m=${m:-0}
        misses=$((misses + m))
        [ "$m" -gt "$worst" ] && worst=$m
      done
      cycles=$(( (seconds * 1000 + 1) * n / 2 ))
      per_job=$((seconds * 1000 + 1))
      # CPU over the whole busy window (job set-up included), per axis and per second of run.
      cpu=$(awk -v t=$((after - before)) -v hz="$hz" -v n="$n" -v s="$seconds" \
        'BEGIN { printf "%.1f %%", 100 * t / hz / n / s }')
      note=""
      [ "$failed" -gt 0 ] && note=" ($failed jobs failed)"
      echo "| $n | $((n / 2)) | ${#nodes[@]} | $sched | $cycles | $misses ($(percent "$misses" "$cycles") %)$note |" \
        "$(percent "$worst" "$per_job") % | $cpu of a core |"
      : "$wall_ns"
    done
  done
  echo
fi
