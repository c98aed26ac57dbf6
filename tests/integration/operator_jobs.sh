#!/usr/bin/env bash
# What an operator does with jobs, on loopback in lockstep, with a client token and an admin
# token: Ctrl-C on `netmc run` cancels its job (`netmc status` shows it cancelled) and the job
# queued behind it, which `netmc status` showed waiting for it, starts at once; `netmc cancel`
# of another connection's job is refused with the client token and done with the admin token, and
# a job from `netmc submit` is cancelled from another connection with the job token it saved
# (refused without it or with a wrong one);
# a job from `netmc submit` runs on without its client, and `netmc watch` follows it from other
# connections, joining mid-run or after its end, with the result `netmc sim` gives.
# Usage: operator_jobs.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
now_ms() { date +%s%3N; }

head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/token"
head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/admin"
start x "$netmc_axis" --node ox --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node oy --axes y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --token-file "$tmp/token" --admin-token-file "$tmp/admin"
port=$(server_port 127.0.0.1)
export NETMC_TOKEN_FILE=$tmp/token
export XDG_STATE_HOME=$tmp/state  # where netmc submit keeps the jobs' cancel tokens
server=(--server "127.0.0.1:$port")
long=(--controller adrc+ilccc --iterations 500)

# state JOB: the job's state as `netmc status JOB` prints it.
state() { "$netmc" status "$1" "${server[@]}" 2>/dev/null | awk -v id="$1" '$1 == id { print $2 }'; }
wait_state() {  # JOB STATE SECONDS
  local until=$(( $(now_ms) + $3 * 1000 ))
  while [ "$(state "$1")" != "$2" ]; do
    [ "$(now_ms)" -lt "$until" ] || { echo "FAIL: job $1 is not $2 after $3 s"; "$netmc" status "${server[@]}"; exit 1; }
    sleep 0.05
  done
}

for _ in $(seq 100); do
  [ "$("$netmc" nodes "${server[@]}" | grep -c '^o[xy] ')" -eq 2 ] && break
  sleep 0.1
done
# Job 1, long; `env --default-signal=INT`: a background job of a script starts with SIGINT ignored.
env --default-signal=INT "$netmc" run "${server[@]}" --quiet "${long[@]}" >"$tmp/first.txt" 2>&1 &
first_pid=$!
wait_state 1 running 20
until "$netmc" status 1 "${server[@]}" | grep -q "running  *[1-9][0-9]*/500"; do sleep 0.05; done
# Job 2 on the same axes waits behind it, and says so.
"$netmc" run "${server[@]}" --quiet --controller adrc --iterations 1 --json "$tmp/second.json" >"$tmp/second.txt" 2>&1 &
second_pid=$!
wait_state 2 queued 10
for _ in $(seq 40); do
  "$netmc" status "${server[@]}" >"$tmp/status.txt"
  grep -q "waits for job 1 (axis x)" "$tmp/status.txt" && break
  sleep 0.05
done
cat "$tmp/status.txt"
grep -q "^ *2 *queued .*waits for job 1 (axis x)" "$tmp/status.txt" || { echo "FAIL: job 2 does not say what it waits for"; exit 1; }

kill -INT "$first_pid"
interrupted=$(now_ms)
first_rc=0
wait "$first_pid" || first_rc=$?
[ "$first_rc" -ne 0 ] || { echo "FAIL: netmc run exited 0 after Ctrl-C"; exit 1; }
wait_state 1 cancelled 5
"$netmc" status 1 "${server[@]}" | grep -q "its client disconnected" || { echo "FAIL: the status does not say why"; exit 1; }
cancelled_ms=$(( $(now_ms) - interrupted ))
wait "$second_pid" || { echo "FAIL: job 2 failed"; cat "$tmp/second.txt"; exit 1; }
second_ms=$(( $(now_ms) - interrupted ))
"$netmc" status 1 "${server[@]}"
echo "Ctrl-C on netmc run: job 1 cancelled after $cancelled_ms ms; job 2, queued behind it, done $second_ms ms after the Ctrl-C"
[ "$second_ms" -lt 10000 ] || { echo "FAIL: job 2 did not start at once"; exit 1; }

# netmc cancel: another connection's job.
"$netmc" run "${server[@]}" --quiet "${long[@]}" >"$tmp/third.txt" 2>&1 &
third_pid=$!
wait_state 3 running 20
refused=0
"$netmc" cancel 3 "${server[@]}" >"$tmp/cancel.txt" 2>&1 || refused=$?
[ "$refused" -ne 0 ] && grep -q "submitted on another connection" "$tmp/cancel.txt" ||
  { echo "FAIL: netmc cancel without the admin token was not refused"; cat "$tmp/cancel.txt"; exit 1; }
echo "netmc cancel 3 with the client token: $(tail -n 1 "$tmp/cancel.txt")"
NETMC_TOKEN_FILE=$tmp/admin "$netmc" cancel 3 "${server[@]}"
wait_state 3 cancelled 5
third_rc=0
wait "$third_pid" || third_rc=$?
[ "$third_rc" -ne 0 ] && grep -q "job 3 .* cancelled: cancelled by an admin" "$tmp/third.txt" ||
  { echo "FAIL: the cancelled job's client did not say so"; cat "$tmp/third.txt"; exit 1; }
echo "netmc cancel 3 with the admin token: cancelled; its client: $(tail -n 1 "$tmp/third.txt")"
# netmc submit, then netmc watch: a job that outlives its client, followed from other connections.
"$netmc" submit "${server[@]}" --quiet --controller adrc+ilccc --iterations 30 --duration 4s >"$tmp/submitted.txt"
job=$(cat "$tmp/submitted.txt")
[ "$job" = 4 ] || { echo "FAIL: netmc submit printed '$job', expected the job id 4"; exit 1; }
wait_state 4 running 20
until "$netmc" status 4 "${server[@]}" | grep -q "running  *\([5-9]\|[12][0-9]\)/30"; do sleep 0.05; done
# Joins mid-run: every iteration, the earlier ones first, in order, then the table.
"$netmc" watch 4 "${server[@]}" --json "$tmp/watch-live.json" >"$tmp/watch-live.txt" 2>&1 ||
  { echo "FAIL: netmc watch of a running job"; cat "$tmp/watch-live.txt"; exit 1; }
head -n 3 "$tmp/watch-live.txt"
seen=$(sed -n 's/.*\[adrc+ilccc\] iteration \([0-9]*\)\/30 .*/\1/p' "$tmp/watch-live.txt" | tr '\n' ' ')
[ "$seen" = "$(seq -s ' ' 1 30) " ] || { echo "FAIL: netmc watch showed iterations '$seen', expected 1..30 in order"; exit 1; }
grep -q "^adrc+ilccc " "$tmp/watch-live.txt" || { echo "FAIL: netmc watch printed no table"; exit 1; }
# After the end: the same result at once, and the same as the in-process run.
"$netmc" watch 4 "${server[@]}" --quiet --json "$tmp/watch-ended.json" >/dev/null
cmp -s "$tmp/watch-live.json" "$tmp/watch-ended.json" ||
  { echo "FAIL: watching the ended job gave another result"; exit 1; }
"$netmc" sim --quiet --controller adrc+ilccc --iterations 30 --duration 4s --json "$tmp/sim-30.json" >/dev/null
same_json "$tmp/sim-30.json" "$tmp/watch-live.json" "netmc submit + watch (job 4, 30 iterations)"
# The watch saw job 4 end: the cancel token its submit saved is gone (job 3's, never submitted, was
# never there; the directory stays).
[ -d "$XDG_STATE_HOME/netmc/jobs" ] && [ ! -e "$XDG_STATE_HOME/netmc/jobs/127.0.0.1_$port-job-4.token" ] ||
  { echo "FAIL: the token of ended job 4 was kept:"; ls -la "$XDG_STATE_HOME/netmc/jobs"; exit 1; }
# netmc submit keeps each job's cancel token (0600, in a 0700 directory): netmc cancel from
# another connection finds it; without it, or with a wrong one, the cancel is refused.
"$netmc" submit "${server[@]}" --quiet "${long[@]}" >"$tmp/submitted-long.txt"
running_job=$(cat "$tmp/submitted-long.txt")
wait_state "$running_job" running 20
"$netmc" submit "${server[@]}" --quiet --controller adrc --iterations 1 >"$tmp/submitted-queued.txt"
queued_job=$(cat "$tmp/submitted-queued.txt")
wait_state "$queued_job" queued 10
token_file=$XDG_STATE_HOME/netmc/jobs/127.0.0.1_$port-job-$queued_job.token
[ "$(stat -c %a "$token_file")" = 600 ] && [ "$(stat -c %a "$XDG_STATE_HOME/netmc/jobs")" = 700 ] ||
  { echo "FAIL: the job token is not private:"; ls -la "$XDG_STATE_HOME/netmc/jobs"; exit 1; }
refused=0
XDG_STATE_HOME=$tmp/another-user "$netmc" cancel "$queued_job" "${server[@]}" >"$tmp/cancel-no-token.txt" 2>&1 ||
  refused=$?
[ "$refused" -ne 0 ] && grep -q "with its job token" "$tmp/cancel-no-token.txt" ||
  { echo "FAIL: netmc cancel without the job token was not refused"; cat "$tmp/cancel-no-token.txt"; exit 1; }
head -c 32 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/wrong-token"
refused=0
"$netmc" cancel "$queued_job" "${server[@]}" --job-token-file "$tmp/wrong-token" >"$tmp/cancel-wrong.txt" 2>&1 ||
  refused=$?
[ "$refused" -ne 0 ] && grep -q "not its token" "$tmp/cancel-wrong.txt" ||
  { echo "FAIL: netmc cancel with a wrong job token was not refused"; cat "$tmp/cancel-wrong.txt"; exit 1; }
[ "$(state "$queued_job")" = queued ] || { echo "FAIL: a refused cancel ended job $queued_job"; exit 1; }
"$netmc" cancel "$queued_job" "${server[@]}" >/dev/null
wait_state "$queued_job" cancelled 5
[ ! -e "$token_file" ] || { echo "FAIL: the cancelled job's token file is still there: $token_file"; exit 1; }
"$netmc" status "$queued_job" "${server[@]}" | grep -q "cancelled with its job token" ||
  { echo "FAIL: the status does not say how job $queued_job was cancelled"; exit 1; }
"$netmc" cancel "$running_job" "${server[@]}" >/dev/null
wait_state "$running_job" cancelled 5
echo "netmc cancel $queued_job (queued) from another connection: refused without its job token and with a" \
  "wrong one, done with it (its token file then deleted); job $running_job (running) likewise"

unknown=0
"$netmc" watch 99 "${server[@]}" >"$tmp/watch-unknown.txt" 2>&1 || unknown=$?
[ "$unknown" -ne 0 ] && grep -q "watch: no job 99" "$tmp/watch-unknown.txt" ||
  { echo "FAIL: netmc watch of an unknown job"; cat "$tmp/watch-unknown.txt"; exit 1; }
echo "netmc watch 99: exit $unknown, $(cat "$tmp/watch-unknown.txt")"

echo "server log:"
sed 's/^/  /' "$tmp/server.log"
