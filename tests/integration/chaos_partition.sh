#!/usr/bin/env bash
# Network partition mid-job: netmc-server and the axis nodes x and y on lab hosts of their own
# (lab.sh), and nftables on the lab's bridge drops every frame between the server's host and axis
# x's host for each of SECONDS... (one job each), while a job in CLOCK mode runs. Axis y keeps
# its network. For every partition:
#   - the nft counters show frames dropped (the partition was real);
#   - the job ends: a partition longer than the server's patience (realtime: --axis-silence,
#     500 ms here; lockstep: --axis-timeout, 1000 ms here) fails it with a message naming axis x
#     (client exit 1, the server's log says so); a shorter one lets a lockstep job complete with
#     the results of netmc sim, and fails a realtime job naming axis x's quick stop (its node
#     reports it when the partition heals): a job whose axis stopped mid-iteration does not
#     "complete", and no axis trips (before, the server ran its loops on to the end on x's stale
#     feedback, winding them up until a command could trip x or, through the cross-coupling, y);
#   - realtime: axis x quick-stops on its watchdog (--watchdog, 50 ms here): its log says
#     "no setpoint for N ms ... quick stop" with N within the watchdog plus scheduling slack;
#   - lockstep: nothing acts without a setpoint, so no watchdog is involved: the axis waits;
#   - the NEXT job on the same server and nodes runs to completion (after the last partition too).
# Usage: chaos_partition.sh BUILD_DIR CLOCK SECONDS...   (root, nftables; else exit 77)
source "$(dirname "$0")/lib.sh" "$@"
clock=$2
shift 2
lengths=("$@")
source "$here/lab.sh"
lab_keep_logs
lab_init
lab_need_nft
for h in srv ax ay; do lab_host "$h"; done
axis_timeout_ms=1000
silence_ms=500
watchdog_ms=50

lab_start server srv -- "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" \
  --transport udp --interface eth0 --axis-timeout "$axis_timeout_ms" --axis-silence "$silence_ms"
for a in x y; do
  lab_start "$a" "a$a" -- "$netmc_axis" --node "part-$a" --axes "$a" --clock "$clock" \
    --domain "$domain" --transport udp --interface eth0 --watchdog "$watchdog_ms"
done
lab_wait_log server 'listening on' 10 || lab_fail "netmc-server did not start"
lab_wait_log x serving 10 || lab_fail "axis x did not start"
lab_wait_log y serving 10 || lab_fail "axis y did not start"
port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/server.log")
# Realtime: 2 iterations of 3 s. Lockstep runs faster than the wall clock, so more of them, long
# enough that a partition 1 s into the job falls inside it.
if [ "$clock" = realtime ]; then job=(--iterations 2 --duration 3s); else job=(--iterations 40 --duration 3s); fi
jobs_run=0
# Lockstep loses nothing (reliable, repaired after the partition): a job it lets complete must
# still equal netmc sim.
[ "$clock" != lockstep ] || "$netmc" sim --controller adrc+ilccc "${job[@]}" --json "$tmp/sim.json" >/dev/null

# run_job TAG: the job in the background from the server's host (management over its loopback).
run_job() {
  jobs_run=$((jobs_run + 1))
  lab_start "job-$1" srv -- "$netmc" run --server "127.0.0.1:$port" --clock "$clock" --controller adrc+ilccc \
    "${job[@]}" --json "$tmp/$1.json"
}
job_ends() {  # TAG LIMIT_S: the client's exit status
  local st=0
  lab_wait "job-$1" "$2" || st=$?
  [ "$st" -ne 124 ] || lab_fail "job $1 still running after $2 s"
  return "$st"
}
must_complete() {  # TAG
  job_ends "$1" 120 || lab_fail "the job after the partition failed (exit $?): $(tail -n 3 "$tmp/job-$1.log")"
  grep -q '"e_sum_m"' "$tmp/$1.json" || lab_fail "job $1 wrote no results"
  echo "$clock: job $1 after the partition completed"
}

for seconds in "${lengths[@]}"; do
  tag=p$((jobs_run + 1))-${seconds/./_}s
  run_job "$tag"
  # 1 s into the job (its first iteration is running: lockstep and realtime both start within it).
  lab_wait_log server "job $jobs_run" 10 || lab_fail "job $jobs_run did not start"
  sleep 1
  cut_at=$EPOCHREALTIME
  lab_partition srv ax on
  sleep "$seconds"
  dropped=$(lab_partition_dropped srv ax)
  lab_partition srv ax off
  heal_at=$EPOCHREALTIME
  cut_ms=$(awk -v a="$cut_at" -v b="$heal_at" 'BEGIN { printf "%d", (b - a) * 1000 }')
  [ "$dropped" -gt 0 ] || lab_fail "the ${seconds} s partition dropped no frame"
  st=0
  job_ends "$tag" 120 || st=$?
  long=$(awk -v s="$seconds" -v c="$clock" -v t="$axis_timeout_ms" -v q="$silence_ms" \
    'BEGIN { print (s * 1000 > (c == "realtime" ? q : t) * 1.5) ? 1 : 0 }')
  short=$(awk -v s="$seconds" -v c="$clock" -v t="$axis_timeout_ms" -v q="$silence_ms" \
    'BEGIN { print (s * 1000 < (c == "realtime" ? q : t) / 2) ? 1 : 0 }')
  outcome=completed
  if [ "$st" -ne 0 ]; then
    outcome="failed: $(grep -m1 -o 'failed: .*' "$tmp/job-$tag.log" | cut -c9- || tail -n 1 "$tmp/job-$tag.log")"
    # When the server ended it, against the cut and the heal (its log's wall-clock stamp).
    failed_at=$(grep -m1 "job $jobs_run failed" "$tmp/server.log" | cut -d' ' -f1-2 || true)
    if [ -n "$failed_at" ]; then
      failed_s=$(date -d "$failed_at" +%s.%N)
      outcome+=" (ended $(awk -v a="$cut_at" -v b="$heal_at" -v f="$failed_s" \
        'BEGIN { printf "%d ms after the cut, %d ms after the heal", (f - a) * 1000, (f - b) * 1000 }'))"
    fi
  fi
  [ "$long" -eq 0 ] || [ "$st" -ne 0 ] || lab_fail "$clock: the job completed through a ${seconds} s partition"
  # No axis trips, but one: realtime ends the job once x stops (its quick stop, reported at the
  # heal, or its silence), lockstep computes nothing without every axis's feedback. While x is
  # cut off, before the server's silence limit, the server's loops run on x's newest (stale)
  # feedback, and through the cross-coupling y may get a command beyond its limit (seen once in
  # a 2 s partition): a clear reason, latched until its operator resets it (done here).
  tripped=$(grep -o 'axis [xy] tripped: .*' "$tmp/job-$tag.log" | head -n 1 || true)
  if [ -n "$tripped" ] && ! { [ "$clock" = realtime ] && [ "$short" -eq 0 ] && [[ $tripped == "axis y tripped: command"* ]]; }; then
    lab_fail "$clock: an axis tripped in a ${seconds} s partition: $tripped"
  fi
  if [ "$clock" = lockstep ] && [ "$short" -eq 1 ] && [ "$st" -ne 0 ]; then
    lab_fail "$clock: a ${seconds} s partition failed the job: $outcome"
  fi
  if [ "$clock" = realtime ] && [ "$long" -eq 0 ]; then
    [ "$st" -ne 0 ] || lab_fail "realtime: the job completed though axis x quick-stopped in it"
    grep -q "job $jobs_run failed: axis x cannot run the job: quick stop after" "$tmp/server.log" ||
      lab_fail "job $jobs_run: the server's log does not name axis x's quick stop: $outcome"
  fi
  if [ "$st" -ne 0 ]; then
    grep -q "job $jobs_run failed: axis x" "$tmp/server.log" ||
      lab_fail "job $jobs_run: no failure naming axis x in the server's log"
  fi
  stop=""
  if [ "$clock" = realtime ]; then
    # At the heal, axis x must be in quick stop: the newest of its quick-stop and end-of-iteration
    # lines for this job up to then is a quick stop (a stall of this loaded host may have stopped
    # it earlier in the same iteration; then the partition found it stopped already).
    heal=$(date -d "@$heal_at" '+%F %T.%3N')
    last=$(awk -v heal="$heal" -v job="axis x job $jobs_run iteration" '
      index($0, job) && ($1 " " $2) <= heal && (/quick stop/ || / samples, /) { line = $0 }
      END { print line }' "$tmp/x.log")
    [[ $last == *"quick stop"* ]] || lab_fail "axis x was not in quick stop at the end of the ${seconds} s partition"
    ms=$(sed -E 's/.*no setpoint for ([0-9]+) ms.*/\1/' <<<"$last")
    # The watchdog is checked at each sample (5 ms); a loaded 2-core host adds its stalls.
    [ "$ms" -le $((watchdog_ms + 250)) ] || lab_fail "axis x quick-stopped after $ms ms without setpoints (watchdog $watchdog_ms ms)"
    stop="; axis x in quick stop at the heal (stopped after $ms ms without setpoints, at $(cut -c12-23 <<<"$last"))"
  fi
  if [ "$st" -eq 0 ] && [ "$clock" = lockstep ]; then
    same_json "$tmp/sim.json" "$tmp/$tag.json" "lockstep job through a ${seconds} s partition" || lab_fail "results changed"
  fi
  echo "$clock: ${seconds} s partition srv<->ax at $(date -d "@$cut_at" +%T.%3N) (${cut_ms} ms from cut to heal, $dropped frames dropped): job $outcome$stop"
  if [ -n "$tripped" ]; then
    lab_kill y USR1   # the operator's reset (netmc reset NODE does the same with the admin token)
    sleep 1
  fi
  run_job "after-$tag"
  must_complete "after-$tag"
done
kill -0 "$(lab_pid server)" || lab_fail "netmc-server died"
