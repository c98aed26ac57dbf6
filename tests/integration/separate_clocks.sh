#!/usr/bin/env bash
# Realtime ILC across hosts with unrelated clocks. netmc-server, two netmc-axis nodes and the client
# each run on a lab host of their own (lab.sh: network namespaces on a bridge, UDP only), and the
# server and both axes also in time namespaces of their own, each with a CLOCK_MONOTONIC days apart:
#   server  +2 days (172800 s)   - the reference
#   axis x  +5 hours (18000 s)   - node minus server: -154800 s (-43 h), a NEGATIVE offset
#   axis y  +3 days (259200 s)   - node minus server:  +86400 s (+24 h)
# (A negative offset relative to the machine may not exceed its uptime, so the server is shifted
# forward instead and x is negative relative to the server.)
#  (a) `netmc nodes --json` from the client host: each node's measured clock offset must equal the
#      difference of the two --monotonic values. That difference is exact (the kernel adds each
#      namespace's constant to the same clock; no start-up jitter enters it), so the only error is
#      the two-way time transfer's: at most half the round trip of the probe used (t1 <= t2, t3 <= t4
#      bracket the exchange), plus 10 us for rounding.
#  (b) `netmc run --clock realtime --controller adrc+ilccc --iterations 5` from the client host must
#      finish and cut e_sum by >= 80 % from iteration 1 to 5 (as realtime_ilc.sh); its one-way delay
#      split (tau_sc, tau_ca) must be plausible (not off by hours: within +-clock_uncertainty of
#      [0, 20 ms], tau_ca >= the emulated 0.3 ms).
#  (c) Baseline: the same hosts, no time namespaces, `--iterations 2`: offsets ~ 0 and the delay
#      statistics must agree with (b) (tolerances below).
# Needs root, iproute2 and time namespaces (unshare --time); exits 77 (skipped) otherwise.
# Set NETMC_KEEP_LOGS=DIR to keep all logs. Usage: separate_clocks.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
source "$here/lab.sh"
lab_keep_logs
server_bin=$netmc_server
axis_bin=$netmc_axis
lab_init
lab_need_timens
t_start=$EPOCHREALTIME


for h in srv ax ay cl; do lab_host "$h"; done
S=$(lab_addr srv)

# start_cluster TAG SERVER_MONO X_MONO Y_MONO: server and both realtime axes, each in its host and
# (MONO not "-") in a time namespace with CLOCK_MONOTONIC + MONO s. Sets $port.
start_cluster() {
  local tag=$1 smono=$2 xmono=$3 ymono=$4 t=()
  t=(); [ "$smono" = - ] || t=(--monotonic "$smono")
  lab_start "server$tag" srv "${t[@]}" -- "$server_bin" --listen "$S:0" --domain "$domain" \
    --transport udp --interface "$S"
  t=(); [ "$xmono" = - ] || t=(--monotonic "$xmono")
  lab_start "x$tag" ax "${t[@]}" -- "$axis_bin" --node host-x --axes x --clock realtime \
    --domain "$domain" --transport udp --interface "$(lab_addr ax)" --watchdog 200
  t=(); [ "$ymono" = - ] || t=(--monotonic "$ymono")
  lab_start "y$tag" ay "${t[@]}" -- "$axis_bin" --node host-y --axes y --clock realtime \
    --domain "$domain" --transport udp --interface "$(lab_addr ay)" --watchdog 200
  lab_wait_log "server$tag" 'listening on' 10 || lab_fail "netmc-server$tag did not start"
  port=$(sed -n "s/.*listening on $S:\([0-9]*\).*/\1/p" "$tmp/server$tag.log")
}

# nodes_table FILE: `netmc nodes --json` from the client host; prints "node measured offset rtt"
# per node (the reply is protobuf JSON, one field a line).
nodes_table() {
  lab_exec cl -- "$netmc" nodes --server "$S:$port" --json >"$1"
  awk -F': ' '
    { v = $2; gsub(/[",]/, "", v) }
    /^ *"node":/ { n = v; m[n] = "false"; o[n] = "nan"; r[n] = "nan" }
    /^ *"clock_measured":/ { m[n] = v }
    /^ *"clock_offset_s":/ { o[n] = v }
    /^ *"round_trip_s":/ { r[n] = v }
    END { for (n in m) print n, m[n], o[n], r[n] }' "$1" | sort
}

# wait_measured TAG: until both nodes have a clock measurement, then 3.3 s more so the server's
# window of 32 probes (one per 100 ms) is full and the best one is picked.
wait_measured() {
  local n
  for _ in $(seq 100); do
    n=$(nodes_table "$tmp/nodes$1.json" | awk '$2 == "true"' | wc -l)
    [ "$n" -eq 2 ] && break
    sleep 0.2
  done
  [ "$n" -eq 2 ] || lab_fail "after 20 s, $n of 2 nodes have a measured clock ($(cat "$tmp/nodes$1.json"))"
  sleep 3.3
}

# check_offsets TAG EXPECTED_X EXPECTED_Y: measured offsets against the expected ones.
check_offsets() {
  local tag=$1
  lab_exec cl -- "$netmc" nodes --server "$S:$port"
  nodes_table "$tmp/nodes$tag.json" >"$tmp/offsets$tag.txt"
  awk -v ex="$2" -v ey="$3" '
    BEGIN { e["host-x"] = ex; e["host-y"] = ey; margin = 10e-6; bad = 0 }
    {
      if (!($1 in e)) next
      seen[$1] = 1
      diff = $3 - e[$1]; bound = $4 / 2 + margin
      ad = diff < 0 ? -diff : diff
      ok = ($2 == "true" && ad <= bound)
      printf "  %s: measured %+.6f s, expected %+d s, difference %+.1f us, bound +-%.1f us" \
        " (rtt/2 %.1f us + 10 us): %s\n", $1, $3, e[$1], diff * 1e6, bound * 1e6, $4 / 2 * 1e6,
        ok ? "ok" : "WRONG"
      if (!ok) bad = 1
    }
    END { if (!seen["host-x"] || !seen["host-y"]) { print "  a node is missing"; bad = 1 }; exit bad }
  ' "$tmp/offsets$tag.txt"
}

# check_stable FILE: fails if an iteration diverged (a starved machine: see the delays).
check_stable() {
  local diverged
  diverged=$(awk '$12 >= 0 { printf "iteration %d diverged at t = %.3f s (tau max %.1f ms)", NR, $12, $5 * 1e3; exit }' "$1")
  [ -z "$diverged" ] || lab_fail "realtime job: $diverged; load average $(cut -d' ' -f1-3 /proc/loadavg)"
}

# run_job TAG ITERATIONS: the realtime paper-001 job from the client host, JSON in $tmp/runTAG.json.
# In the background (lab_start), so that SIGTERM/SIGINT stop the test at once, not after the job.
run_job() {
  local tag=$1 rc=0 t0=$EPOCHREALTIME
  lab_start "run$tag" cl -- "$netmc" run --server "$S:$port" --clock realtime --controller adrc+ilccc \
    --iterations "$2" --curve --json "$tmp/run$tag.json"
  lab_wait "run$tag" 120 || rc=$?
  [ "$rc" -ne 124 ] || lab_stop "run$tag"
  grep -E 'iteration [0-9]+/' "$tmp/run$tag.log" | sed 's/^ */  /' || true
  echo "  (job took $(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }') s, exit $rc;" \
    "load average $(cut -d' ' -f1-3 /proc/loadavg))"
  [ "$rc" -eq 0 ] || lab_fail "realtime job ($tag) exit $rc (124: still running after 120 s): $(tail -n 3 "$tmp/run$tag.log")"
}

# per_iteration FILE: one line per iteration: e_sum tau_mean tau_p50 tau_p99 tau_max tau_sc_mean
# tau_ca_mean lost_feedback lost_setpoints deadline_misses clock_uncertainty diverged_at (seconds,
# metres; diverged_at -1: stable).
per_iteration() { iteration_fields "$1" e_sum_m tau_mean_s tau_p50_s tau_p99_s tau_max_s tau_sc_mean_s tau_ca_mean_s lost_feedback lost_setpoints deadline_misses clock_uncertainty_s diverged_at_s; }

print_stats() {
  awk '{
    printf "  iteration %d: e_sum %7.3f mm  tau mean %.3f  p50 %.3f  p99 %.3f  max %.3f ms" \
      "  tau_sc %.3f  tau_ca %.3f ms  +-%.1f us  lost fb/sp %d/%d  deadline misses %d\n",
      NR, $1 * 1e3, $2 * 1e3, $3 * 1e3, $4 * 1e3, $5 * 1e3, $6 * 1e3, $7 * 1e3, $11 * 1e6, $8, $9, $10
  }' "$1"
}

# --- (a) unrelated clocks: measured offsets ----------------------------------------------------
srv_mono=172800 x_mono=18000 y_mono=259200
echo "clocks: server CLOCK_MONOTONIC +${srv_mono} s, axis x +${x_mono} s, axis y +${y_mono} s" \
  "(machine uptime $(awk '{printf "%d", $1}' /proc/uptime) s)"
start_cluster "" "$srv_mono" "$x_mono" "$y_mono"
wait_measured ""
echo "(a) clock offsets (node minus server) measured by the server, seen from host cl:"
check_offsets "" $((x_mono - srv_mono)) $((y_mono - srv_mono)) || lab_fail "measured clock offsets"

# --- (b) realtime ILC across the unrelated clocks ----------------------------------------------
echo "(b) realtime adrc+ilccc, 5 iterations, clocks 43 h behind / 24 h ahead of the server:"
run_job "" 5
per_iteration "$tmp/run.json" >"$tmp/stats.txt"
print_stats "$tmp/stats.txt"
check_stable "$tmp/stats.txt"
[ "$(wc -l <"$tmp/stats.txt")" -eq 5 ] || lab_fail "expected 5 iterations in the JSON"
awk '
  NR == 1 { first = $1 } { last = $1 }
  END {
    cut = 1 - last / first
    printf "  e_sum %.3f mm (iteration 1, ADRC) -> %.3f mm (iteration 5): cut %.1f %% (need >= 80 %%)\n",
      first * 1e3, last * 1e3, cut * 100
    exit (cut >= 0.80) ? 0 : 1
  }' "$tmp/stats.txt" || lab_fail "ADRC+ILCCC did not cut e_sum by 80 % across unrelated clocks"
# The split into tau_sc (sensor -> controller) and tau_ca (controller -> actuator) subtracts
# timestamps of different clocks: a wrong offset shows up as hours, or as negative delays.
awk '{
  u = $11
  if (u <= 0 || u > 5e-3) { printf "  iteration %d: clock_uncertainty_s %g not in (0, 5 ms]\n", NR, u; bad = 1 }
  if ($6 < -u || $6 > 20e-3 + u) { printf "  iteration %d: tau_sc_mean %g s implausible\n", NR, $6; bad = 1 }
  if ($7 < 0.3e-3 - u || $7 > 20e-3 + u) { printf "  iteration %d: tau_ca_mean %g s implausible\n", NR, $7; bad = 1 }
} END { exit bad }' "$tmp/stats.txt" || lab_fail "delay split across clocks"
echo "  tau_sc and tau_ca plausible in every iteration (within +-clock_uncertainty of 0..20 ms," \
  "tau_ca >= 0.3 ms emulated)"

# --- (c) same-clock baseline -------------------------------------------------------------------
for p in server x y; do lab_stop "$p"; done
echo "(c) baseline: the same hosts, one clock (no time namespaces)"
start_cluster _base - - -
wait_measured _base
check_offsets _base 0 0 || lab_fail "measured clock offsets on one clock"
run_job _base 2
per_iteration "$tmp/run_base.json" >"$tmp/stats_base.txt"
print_stats "$tmp/stats_base.txt"
check_stable "$tmp/stats_base.txt"
[ "$(wc -l <"$tmp/stats_base.txt")" -eq 2 ] || lab_fail "expected 2 iterations in the baseline JSON"

# Realtime delays vary from run to run with scheduling and the load on the machine (2 cores: the
# server, two axes and DDS threads share them), and p99 lies in the tail, which a few preemptions
# move by milliseconds. Unrelated clocks must not change the delays themselves (the offsets only
# enter the schedule, once per iteration, and the tau split), so the mean of the iterations' tau_mean
# must agree within 0.5 ms (the emulated delay alone is 0.55 ms), and the mean tau_p99 within 2 ms
# or a factor of 2 (either suffices).
compare_delays() {  # BASELINE_STATS
  awk -v f="$tmp/stats.txt" -v g="$1" 'BEGIN {
  while ((getline line < f) > 0) { split(line, a, " "); m1 += a[2]; p1 += a[4]; n1++ }
  while ((getline line < g) > 0) { split(line, a, " "); m2 += a[2]; p2 += a[4]; n2++ }
  m1 /= n1; p1 /= n1; m2 /= n2; p2 /= n2
  dm = m1 - m2; adm = dm < 0 ? -dm : dm
  dp = p1 - p2; adp = dp < 0 ? -dp : dp
  ratio = p1 > p2 ? p1 / p2 : p2 / p1
  okm = adm <= 0.5e-3; okp = (adp <= 2e-3 || ratio <= 2)
  printf "tau_mean: unrelated clocks %.3f ms, one clock %.3f ms: difference %+.3f ms (limit 0.5 ms): %s\n",
    m1 * 1e3, m2 * 1e3, dm * 1e3, okm ? "ok" : "WRONG"
  printf "tau_p99:  unrelated clocks %.3f ms, one clock %.3f ms: difference %+.3f ms, ratio %.2f" \
    " (limit 2 ms or x2): %s\n", p1 * 1e3, p2 * 1e3, dp * 1e3, ratio, okp ? "ok" : "WRONG"
  exit (okm && okp) ? 0 : 1
}'
}
# A stretch of seconds in which the shared machine delays every process (seen once here: p99 13 ms
# against 2 ms in both runs before and after) moves one run's tail by far more: a disagreement is
# measured once more on a second baseline, and only one seen against both fails.
if ! compare_delays "$tmp/stats_base.txt"; then
  echo "  once more: a second baseline job on the same hosts"
  run_job _again 2
  per_iteration "$tmp/run_again.json" >"$tmp/stats_again.txt"
  print_stats "$tmp/stats_again.txt"
  compare_delays "$tmp/stats_again.txt" || lab_fail "delays differ between unrelated clocks and one clock (twice)"
fi
for p in server_base x_base y_base; do lab_stop "$p"; done

echo "separate clocks passed in $(awk -v a="$t_start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.0f", b - a }') s"
