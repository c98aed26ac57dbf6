#!/usr/bin/env bash
# The server killed with SIGKILL at random moments while clients submit and watch jobs, and
# restarted on the same job store (--state-dir): every job a client saw accepted is there once,
# the job store's integrity check passes after every kill, no iteration a watcher was shown is
# lost, the queue runs to the end after the last restart, and every job that ended done gives
# the JSON of `netmc sim` for its spec; a job that was running when the server died is failed
# with "server restarted during iteration N". A second server on the same store refuses to start,
# naming the first's pid. Then once in realtime: the axes stop on their
# watchdog, and the job queued behind the killed one runs after the restart.
# Usage: chaos_server_killed.sh BUILD_DIR KILLS SEED   (loopback only)
source "$(dirname "$0")/lib.sh" "$@"
kills=${2:-3}
RANDOM=${3:-26}
state=$tmp/state
now_ms() { date +%s%3N; }
port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
server=(--server "127.0.0.1:$port")

generation=0
server_pid=""
# A server on the job store; waits until it listens.
start_server() {  # CLOCK-independent
  generation=$((generation + 1))
  start "server$generation" "$netmc_server" --listen "127.0.0.1:$port" --domain "$domain" \
    --transport udp --state-dir "$state" "$@"
  server_pid=${pids[-1]}
  for _ in $(seq 100); do
    grep -q "listening on 127.0.0.1:$port" "$tmp/server$generation.log" && return 0
    kill -0 "$server_pid" 2>/dev/null || break
    sleep 0.1
  done
  echo "FAIL: netmc-server (generation $generation) did not start:"; cat "$tmp/server$generation.log"; exit 1
}
integrity() {
  local answer
  answer=$(sqlite3 "$state/jobs.sqlite" 'PRAGMA integrity_check')
  [ "$answer" = ok ] || { echo "FAIL: the job store's integrity check after kill $1: $answer"; exit 1; }
}
jobs_json() { "$netmc" jobs "${server[@]}" --limit 10000 --json; }
unfinished() {
  jobs_json | /usr/bin/python3 -c 'import json, sys; print(sum(j.get("state") in ("queued", "running") for j in json.load(sys.stdin).get("jobs", [])))'
}

# --- Lockstep: a stream of submissions and watchers, the server killed KILLS times. ---
start x "$netmc_axis" --node chaos-x --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node chaos-y --axes y --domain "$domain" --transport udp
start_server
# One server per job store: a second one on it refuses to start, naming the first's pid.
second_rc=0
timeout 20 "$netmc_server" --listen 127.0.0.1:0 --domain "$((domain + 1))" --transport udp --state-dir "$state" \
  >"$tmp/second.log" 2>&1 || second_rc=$?
if [ "$second_rc" -eq 0 ] || [ "$second_rc" -eq 124 ] || ! grep -q "another netmc-server (pid $server_pid)" "$tmp/second.log"; then
  echo "FAIL: a second netmc-server on the same --state-dir: exit $second_rc:"; cat "$tmp/second.log"; exit 1
fi
echo "a second server on the same --state-dir: exit $second_rc, $(grep -o 'another netmc-server (pid [0-9]*)' "$tmp/second.log")"
iterations=(6 14 9 20 11 7 16 12 8 18 10 15 5 13 17 19)
submitter() {
  local n id
  for n in "${iterations[@]}"; do
    until id=$("$netmc" submit "${server[@]}" --quiet --controller adrc+ilccc --iterations "$n" --duration 4s 2>/dev/null); do
      sleep 0.2
    done
    echo "$id $n" >>"$tmp/accepted.txt"
    # A watcher of its own: what it is shown must survive the kills.
    "$netmc" watch "$id" "${server[@]}" >"$tmp/watch-$id.log" 2>&1 </dev/null &
    sleep 0.$((RANDOM % 5))
  done
}
: >"$tmp/accepted.txt"
submitter &
submitter_pid=$!
pids+=("$submitter_pid")
for kill in $(seq "$kills"); do
  # Anywhere: while submits are accepted and validated, between and inside iterations.
  sleep "$((RANDOM % 3)).$((RANDOM % 10))"
  kill -KILL "$server_pid"
  wait "$server_pid" 2>/dev/null || true
  integrity "$kill"
  echo "kill $kill of $kills: after $(wc -l <"$tmp/accepted.txt") accepted jobs; integrity ok"
  start_server
done
wait "$submitter_pid"
# The queue runs to the end (each restart waits out its predecessor's holds on the axes: 10 s).
until=$(( $(now_ms) + 600000 ))
while [ "$(unfinished)" != 0 ]; do
  [ "$(now_ms)" -lt "$until" ] || { echo "FAIL: jobs still unfinished after 600 s"; "$netmc" jobs "${server[@]}"; exit 1; }
  sleep 1
done
"$netmc" jobs "${server[@]}" --limit 10000 | tee "$tmp/jobs.txt"
jobs_json >"$tmp/jobs.json"
sleep 1  # the watchers of the last jobs print their ends
/usr/bin/python3 - "$tmp" <<'PY'
import json, re, sys, glob
tmp = sys.argv[1]
jobs = {int(j["job_id"]): j for j in json.load(open(f"{tmp}/jobs.json"))["jobs"]}
accepted = [tuple(map(int, line.split())) for line in open(f"{tmp}/accepted.txt")]
ids = [a for a, _ in accepted]
bad = []
if len(set(ids)) != len(ids): bad.append(f"an id was accepted twice: {ids}")
for job_id, n in accepted:
    job = jobs.get(job_id)
    if job is None: bad.append(f"accepted job {job_id} is lost"); continue
    if int(job.get("iterations_total", 0)) != n: bad.append(f"job {job_id}: {job.get('iterations_total')} iterations, submitted {n}")
    done = int(job.get("iterations_done", 0))
    seen = [int(k) for k in re.findall(r"iteration (\d+)/", open(f"{tmp}/watch-{job_id}.log", errors="replace").read())]
    if seen and max(seen) > done: bad.append(f"job {job_id}: a watcher saw iteration {max(seen)}, the store kept {done}")
    state = job.get("state")
    if state == "done":
        if done != n: bad.append(f"job {job_id} done with {done} of {n} iterations")
    elif state == "failed":
        if not re.fullmatch(rf"server restarted during iteration {done + 1}", job.get("error", "")):
            bad.append(f"job {job_id} failed: {job.get('error')!r}")
    else:
        bad.append(f"job {job_id} ended {state}: {job.get('error')!r}")
unanswered = sorted(set(jobs) - set(ids))
print(f"{len(accepted)} accepted jobs, all there once; {sum(j['state'] == 'done' for j in jobs.values())} done, "
      f"{sum(j['state'] == 'failed' for j in jobs.values())} failed by a restart; "
      f"{len(unanswered)} more whose submit the kill left unanswered (the client submitted again): {unanswered}")
for line in bad: print("FAIL:", line)
sys.exit(1 if bad else 0)
PY
# Every job that ended done: the JSON of netmc sim for its spec.
compared=0
while read -r id n; do
  grep -q "^ *$id  *done " "$tmp/jobs.txt" || continue
  [ -f "$tmp/sim-$n.json" ] ||
    "$netmc" sim --quiet --controller adrc+ilccc --iterations "$n" --duration 4s --json "$tmp/sim-$n.json" >/dev/null
  "$netmc" watch "$id" "${server[@]}" --quiet --json "$tmp/job-$id.json" >/dev/null
  cmp -s "$tmp/sim-$n.json" "$tmp/job-$id.json" || { same_json "$tmp/sim-$n.json" "$tmp/job-$id.json" "job $id"; exit 1; }
  compared=$((compared + 1))
done <"$tmp/accepted.txt"
echo "$compared done jobs: JSON identical to netmc sim"
[ "$compared" -gt 0 ] || { echo "FAIL: no job ended done"; exit 1; }
echo "events of the first jobs: $(sqlite3 "$state/jobs.sqlite" "SELECT count(*) FROM job_events") state changes kept"

# --- Realtime: killed inside an iteration; the axes stop on their watchdog. ---
kill -TERM "$server_pid"
wait "$server_pid" 2>/dev/null || true
# With the server down, netmc jobs --state-dir reads the same history from the store itself.
"$netmc" jobs --state-dir "$state" --limit 10000 --json >"$tmp/jobs-offline.json"
cmp -s "$tmp/jobs.json" "$tmp/jobs-offline.json" ||
  { echo "FAIL: netmc jobs --state-dir differs from the server's list:"; diff "$tmp/jobs.json" "$tmp/jobs-offline.json" | head; exit 1; }
echo "server down: netmc jobs --state-dir lists the same $(grep -c '"job_id"' "$tmp/jobs.json") jobs, byte for byte"
start rx "$netmc_axis" --node chaos-rx --axes u --clock realtime --domain "$domain" --transport udp
start ry "$netmc_axis" --node chaos-ry --axes v --clock realtime --domain "$domain" --transport udp
rx_log=$tmp/rx.log
start_server
realtime=(--clock realtime --axes u,v --controller adrc+ilccc --duration 2s)
first=$("$netmc" submit "${server[@]}" --quiet "${realtime[@]}" --iterations 30)
second=$("$netmc" submit "${server[@]}" --quiet "${realtime[@]}" --iterations 2)
until "$netmc" status "$first" "${server[@]}" | grep -q "running  *[2-9]/30"; do sleep 0.1; done
kill -KILL "$server_pid"
killed=$(now_ms)
wait "$server_pid" 2>/dev/null || true
integrity realtime
for _ in $(seq 50); do grep -q "no setpoint for .*quick stop" "$rx_log" && break; sleep 0.1; done
stop_line=$(grep -m1 "no setpoint for .*quick stop" "$rx_log") || { echo "FAIL: axis u did not stop on its watchdog"; cat "$rx_log"; exit 1; }
stopped=$(date -d "${stop_line:0:23}" +%s%3N)
echo "axis u: quick stop $((stopped - killed)) ms after the kill (watchdog 50 ms): ${stop_line:24}"
[ $((stopped - killed)) -lt 2000 ] || { echo "FAIL: the axis stopped more than 2 s after the server died"; exit 1; }
start_server
until=$(( $(now_ms) + 120000 ))
until "$netmc" status "$second" "${server[@]}" | grep -q "^ *$second  *\(done\|failed\|cancelled\)"; do
  [ "$(now_ms)" -lt "$until" ] || { echo "FAIL: the queued realtime job did not end"; "$netmc" jobs "${server[@]}"; exit 1; }
  sleep 0.5
done
"$netmc" jobs "${server[@]}" --limit 2
"$netmc" status "$first" "${server[@]}" | grep -q "failed .*server restarted during iteration" ||
  { echo "FAIL: the killed realtime job is not failed by the restart"; "$netmc" status "${server[@]}"; exit 1; }
# netmc watch of the failed job: exit 1 naming the failure, its kept iterations in the table and the JSON.
watch_rc=0
"$netmc" watch "$first" "${server[@]}" --quiet --json "$tmp/failed.json" >"$tmp/failed.txt" 2>"$tmp/failed.err" || watch_rc=$?
kept=0
[ ! -f "$tmp/failed.json" ] || kept=$(grep -c '"iteration":' "$tmp/failed.json" || true)
restarted=$(sed -n 's/.*server restarted during iteration \([0-9]*\).*/\1/p' "$tmp/failed.err")
if [ "$watch_rc" -eq 0 ] || [ -z "$restarted" ] || [ "$kept" -ne $((restarted - 1)) ] || ! grep -q "kept iterations" "$tmp/failed.err"; then
  echo "FAIL: netmc watch of the failed job: exit $watch_rc, $kept iterations in its JSON:"; cat "$tmp/failed.err"; exit 1
fi
echo "netmc watch --json of the job failed during iteration $restarted: exit $watch_rc, its $kept kept iterations written"
"$netmc" status "$second" "${server[@]}" | grep -q "^ *$second  *done  *2/2" ||
  { echo "FAIL: the realtime job queued behind it did not run"; "$netmc" status "${server[@]}"; exit 1; }
echo "realtime: killed during iteration $(sed -n 's/.*server restarted during iteration \([0-9]*\).*/\1/p' <("$netmc" status "$first" "${server[@]}")); the queued job ran after the restart"
