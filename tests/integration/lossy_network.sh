#!/usr/bin/env bash
# Random UDP loss on the links between lab hosts (lab.sh: network namespaces on a bridge, nftables).
# netmc-server on host srv, one netmc-axis node per host ax and ay, the client on srv (its TCP
# management connection is never dropped; it stays inside srv anyway).
#
# Loss model: `lab_loss HOST P out` on every host: each UDP datagram is drawn exactly once, on
# its sender's link into the bridge, and lost with probability P, whichever host it goes to. So P
# is the end-to-end loss of every datagram between two hosts, comparable to netmc sim's
# --loss bernoulli:p=P. (`both` would draw each datagram twice, leaving its sender and reaching its
# receiver: 1-(1-P)^2, 36 % at P = 20 %.) A multicast datagram (discovery) is lost for all its
# receivers at once.
#
#  Part A, lockstep (reliable DDS with millisecond heartbeats: a loss is repaired, not counted): at
#    0, 1, 5 and 20 % loss, `netmc run --controller adrc+ilccc --iterations 3` must finish and write
#    JSON byte-identical to `netmc sim` with the same flags. 1 % may cost at most 3 s over the
#    lossless run; 5 % and 20 % must finish within 4 times the lossless time + 20 s (times printed).
#  Part B, realtime (best-effort setpoints and feedback; a lost one is counted, not repaired), the
#    axes restarted with --clock realtime, paper 001's study (8 s iterations at h = 5 ms). The
#    nodes' watchdog is 200 ms here, not 50: eleven setpoints in a row are lost with probability
#    0.05^11 at 5 %, so a 50 ms gap is a host stall (this 2-core virtual machine has them; a CI
#    run saw one of 55 ms), which chaos_starvation.sh tests; this test is about losses. The
#    lossless 80 % cut of realtime_ilc.sh at 1 % loss is not rerun here (it cut 86 %; Part A runs
#    1 % in lockstep):
#     5 %, 5 iterations: ADRC+ILCCC still converges: cut >= 50 %. Not 80 %: netmc sim itself, with
#       5 % Bernoulli loss of setpoints and feedback (--loss/--uplink-loss bernoulli:p=0.05), cuts
#       63-74 % (30 seeds, median 69 %; printed for seed 1): a lost feedback sample makes the server
#       compute with the previous one, and the ILC learns from that cycle too. The model reaches
#       80 % only up to about 2-3 % loss. Realtime runs here scattered 59-72 %.
#    20 %, 2 iterations: finishes; lost_setpoints + lost_feedback > 0.
#    The counted losses must match the link's loss: lost feedback and lost setpoints each within
#    [P/3, 2P + 1 %] of the 2 x 1600 samples of an iteration. Lost counts, deadline misses and
#    delays are printed per loss level.
# Needs root, iproute2 and nftables; exits 77 (skipped) otherwise.
# Set NETMC_KEEP_LOGS=DIR to keep all logs. Usage: lossy_network.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
source "$here/lab.sh"
lab_keep_logs
server_bin=$netmc_server
axis_bin=$netmc_axis
lab_init
lab_need_nft
t_start=$EPOCHREALTIME
hosts=(srv ax ay)

seconds_since() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }'; }

for h in "${hosts[@]}"; do lab_host "$h"; done
S=$(lab_addr srv)

# set_loss P: P % on every host's outgoing UDP (see the header).
set_loss() { local h; for h in "${hosts[@]}"; do lab_loss "$h" "$1" out; done; }

# Frames each host sent into the bridge (its veth's far end, in the bridge namespace), to put the
# nft drop counters in proportion. Prints the sum over the hosts (0 if not readable).
sent_frames() {
  local h n total=0
  for h in "${hosts[@]}"; do
    n=$(ip netns exec "$lab_tag-bridge" cat "/sys/class/net/v$(lab_addr "$h" | cut -d. -f4)/statistics/rx_packets" \
      2>/dev/null || echo 0)
    total=$((total + n))
  done
  echo "$total"
}
dropped_datagrams() { local h total=0; for h in "${hosts[@]}"; do total=$((total + $(lab_loss_dropped "$h"))); done; echo "$total"; }

# run_loss P ITERATIONS LOGNAME [run flags...]: sets P % loss, runs the job from srv (timeout
# 150 s; in the background, so that SIGTERM/SIGINT stop the test at once), prints its wall time
# and the datagrams nft dropped. Sets $rc (124: timed out), $wall; the client's output is in
# $tmp/LOGNAME.log.
run_loss() {
  local pct=$1 iterations=$2 name=$3 t0 f0
  shift 3
  set_loss "$pct"
  f0=$(sent_frames)
  t0=$EPOCHREALTIME
  rc=0
  lab_start "$name" srv -- "$netmc" run --server "$S:$port" --controller adrc+ilccc \
    --iterations "$iterations" --json "$tmp/$name.json" "$@"
  lab_wait "$name" 150 || rc=$?
  wall=$(seconds_since "$t0")
  [ "$rc" -ne 124 ] || lab_stop "$name"
  local dropped frames
  dropped=$(dropped_datagrams)
  frames=$(( $(sent_frames) - f0 ))
  set_loss 0
  echo "  loss $pct %: exit $rc after $wall s; nft dropped $dropped of $frames frames sent" \
    "($(awk -v d="$dropped" -v f="$frames" 'BEGIN { printf "%.1f", f ? 100 * d / f : 0 }') %);" \
    "load average $(cut -d' ' -f1-3 /proc/loadavg)"
}

# start_nodes CLOCK TAG: one axis node per host, waits until the server lists both. A command
# limit of 5 (the plant's rated input is 1): at 20 % loss ILC asks for up to twice the rated input
# for a cycle, which a node with the default limit trips on (right for a real axis; this test
# studies loss, and the job's own command limit still saturates the plant's input).
start_nodes() {
  lab_start "x$2" ax -- "$axis_bin" --node "$2-x" --axes x --clock "$1" --domain "$domain" \
    --transport udp --interface "$(lab_addr ax)" --command-limit 5 --watchdog 200
  lab_start "y$2" ay -- "$axis_bin" --node "$2-y" --axes y --clock "$1" --domain "$domain" \
    --transport udp --interface "$(lab_addr ay)" --command-limit 5 --watchdog 200
  local n=0
  for _ in $(seq 100); do
    n=$(lab_exec srv -- "$netmc" nodes --server "$S:$port" | grep -cE "^$2-[xy] .*idle" || true)
    [ "$n" -eq 2 ] && return 0
    sleep 0.2
  done
  lab_exec srv -- "$netmc" nodes --server "$S:$port"
  lab_fail "the server lists $n of 2 $1 nodes after 20 s"
}

lab_start server srv -- "$server_bin" --listen "$S:0" --domain "$domain" --transport udp --interface "$S"
lab_wait_log server 'listening on' 10 || lab_fail "netmc-server did not start"
port=$(sed -n "s/.*listening on $S:\([0-9]*\).*/\1/p" "$tmp/server.log")

# --- Part A: lockstep ---------------------------------------------------------------------------
study=(--controller adrc+ilccc --iterations 3)
"$netmc" sim --quiet "${study[@]}" --json "$tmp/sim.json" >/dev/null
start_nodes lockstep ls
echo "Part A: lockstep adrc+ilccc, 3 iterations, against netmc sim ($(wc -c <"$tmp/sim.json") bytes of JSON)"
declare -A walls=()
for pct in 0 1 5 20; do
  run_loss "$pct" 3 "lockstep$pct"
  walls[$pct]=$wall
  [ "$rc" -eq 0 ] || lab_fail "lockstep job at $pct % loss: exit $rc: $(tail -n 3 "$tmp/lockstep$pct.log")"
  if cmp -s "$tmp/lockstep$pct.json" "$tmp/sim.json"; then
    echo "    identical JSON to netmc sim"
  else
    diff "$tmp/sim.json" "$tmp/lockstep$pct.json" | head -20
    lab_fail "lockstep at $pct % loss differs from netmc sim"
  fi
done
lab_stop xls
lab_stop yls
# Until the server has dropped them: a new node claiming x while ls-x is listed would be refused
# ("axis x is held by node ls-x") and only accepted on its next announcement.
for _ in $(seq 50); do
  lab_exec srv -- "$netmc" nodes --server "$S:$port" | grep -qE '^ls-[xy] ' || break
  sleep 0.2
done
echo "  wall times: 0 % ${walls[0]} s, 1 % ${walls[1]} s, 5 % ${walls[5]} s, 20 % ${walls[20]} s"
awk -v w0="${walls[0]}" -v w1="${walls[1]}" -v w5="${walls[5]}" -v w20="${walls[20]}" 'BEGIN {
  lim1 = w0 + 3; lim = 4 * w0 + 20
  printf "  1 %%: %+.1f s over lossless (limit +3 s); 5 %%, 20 %%: limit %.1f s (4 x lossless + 20 s)\n", w1 - w0, lim
  exit (w1 <= lim1 && w5 <= lim && w20 <= lim) ? 0 : 1
}' || lab_fail "lockstep under loss too slow"

# --- Part B: realtime ---------------------------------------------------------------------------
start_nodes realtime rt
echo "Part B: realtime adrc+ilccc (best-effort control streams, h = 5 ms, 8 s iterations)"
# rt_stats FILE: per iteration "e_sum tau_mean tau_p99 tau_max tau_sc_mean tau_ca_mean lost_feedback
# lost_setpoints deadline_misses diverged_at" (the JSON has one field a line; diverged_at -1: stable).
rt_stats() { iteration_fields "$1" e_sum_m tau_mean_s tau_p99_s tau_max_s tau_sc_mean_s tau_ca_mean_s lost_feedback lost_setpoints deadline_misses diverged_at_s; }
# 2 axes x 1600 samples (8 s at 5 ms) per iteration: the share of them lost.
print_rt() {
  awk '{
    printf "    iteration %d: e_sum %7.3f mm  tau mean %.3f p99 %.3f max %.3f ms (sc %.3f, ca %.3f)" \
      "  lost feedback %d, setpoints %d (%.1f %%, %.1f %% of 3200)  deadline misses %d\n",
      NR, $1 * 1e3, $2 * 1e3, $3 * 1e3, $4 * 1e3, $5 * 1e3, $6 * 1e3, $7, $8, 100 * $7 / 3200, 100 * $8 / 3200, $9
  }' "$1"
}
# ecut FILE: e_sum cut from the first to the last iteration, in %.
ecut() { awk 'NR == 1 { first = $1 } { last = $1 } END { printf "%.1f", 100 * (1 - last / first) }' "$1"; }
"$netmc" sim --quiet --controller adrc+ilccc --iterations 5 --loss bernoulli:p=0.05 \
  --uplink-loss bernoulli:p=0.05 --json "$tmp/sim_loss5.json" >/dev/null
rt_stats "$tmp/sim_loss5.json" >"$tmp/sim_loss5.txt"
sim_cut5=$(ecut "$tmp/sim_loss5.txt")
for pct in 5 20; do
  iterations=$([ "$pct" = 20 ] && echo 2 || echo 5)
  run_loss "$pct" "$iterations" "realtime$pct" --clock realtime
  [ "$rc" -eq 0 ] || lab_fail "realtime job at $pct % loss: exit $rc: $(tail -n 3 "$tmp/realtime$pct.log")"
  rt_stats "$tmp/realtime$pct.json" >"$tmp/realtime$pct.txt"
  print_rt "$tmp/realtime$pct.txt"
  diverged=$(awk '$10 >= 0 { printf "iteration %d diverged at t = %.3f s (tau max %.1f ms)", NR, $10, $4 * 1e3; exit }' \
    "$tmp/realtime$pct.txt")
  [ -z "$diverged" ] || lab_fail "realtime job at $pct % loss: $diverged; load average $(cut -d' ' -f1-3 /proc/loadavg)"
  [ "$(wc -l <"$tmp/realtime$pct.txt")" -eq "$iterations" ] || lab_fail "expected $iterations iterations at $pct %"
  lost=$(awk '{ n += $7 + $8 } END { print n + 0 }' "$tmp/realtime$pct.txt")
  echo "    lost feedback + setpoints: $lost"
  if [ "$pct" = 20 ] && [ "$lost" -eq 0 ]; then lab_fail "no lost samples counted at 20 % loss"; fi
  awk -v p="$pct" '{
    lo = 3200 * p / 300; hi = 3200 * (2 * p + 1) / 100
    if ($7 < lo || $7 > hi || $8 < lo || $8 > hi) {
      printf "    iteration %d: lost feedback %d, setpoints %d: not within [%.0f, %.0f]\n", NR, $7, $8, lo, hi; bad = 1
    }
  } END { exit bad }' "$tmp/realtime$pct.txt" || lab_fail "lost counts do not match $pct % loss on the links"
  c=$(ecut "$tmp/realtime$pct.txt")
  first_last=$(awk 'NR == 1 { f = $1 } { l = $1 } END { printf "e_sum %.3f mm (iteration 1, ADRC) -> %.3f mm (iteration %d)", f * 1e3, l * 1e3, NR }' \
    "$tmp/realtime$pct.txt")
  case $pct in
    5) echo "    $first_last: cut $c % (need >= 50 %; netmc sim with 5 % loss both ways: $sim_cut5 %)"
       awk -v c="$c" 'BEGIN { exit !(c >= 50) }' || lab_fail "ADRC+ILCCC did not converge at 5 % loss" ;;
    *) echo "    $first_last: cut $c % (not checked)" ;;
  esac
done
lab_stop xrt
lab_stop yrt
lab_stop server
echo "lossy network passed in $(seconds_since "$t_start") s"
