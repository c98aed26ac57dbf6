#!/usr/bin/env bash
# The job store on a full disk and on a read-only one (a tmpfs of 3 MiB in a mount namespace of
# the test's own): the server refuses new jobs with a message that says why, the job that runs
# goes on to its end, the store's integrity check passes, jobs are accepted again once there is
# room; the job that ended while the disk was full is told done only once its end is kept, and
# after a restart the store's history (netmc jobs, with and without the server) is what its
# watcher saw; a server started on a read-only store says why and exits.
# Usage: job_store_disk_full.sh BUILD_DIR   (root; loopback only)
source "$(dirname "$0")/lib.sh" "$@"
if [ -z "${NETMC_IN_MOUNT_NAMESPACE:-}" ]; then
  # Everything below (mounts, processes) lives in a mount namespace of its own.
  exec unshare --mount --propagation private env NETMC_IN_MOUNT_NAMESPACE=1 bash "$0" "$@"
fi
state=$tmp/state
mkdir -p "$state"
mount -t tmpfs -o size=3m tmpfs "$state"
extra_cleanup+=("umount '$state'")
integrity() {
  local answer
  # immutable: a read-only mount has no room for the WAL's shared memory file either.
  answer=$(sqlite3 "file:$state/jobs.sqlite?immutable=1" 'PRAGMA integrity_check' 2>&1) || true
  [ "$answer" = ok ] || { echo "FAIL: integrity check $1: $answer"; exit 1; }
  echo "integrity check $1: ok"
}

start x "$netmc_axis" --node full-x --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node full-y --axes y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --state-dir "$state"
server_pid=${pids[-1]}
port=$(server_port 127.0.0.1)
server=(--server "127.0.0.1:$port")
# 60 iterations (about 11 s): long enough to fill the disk and be refused a submit while it runs.
n=60
long=$("$netmc" submit "${server[@]}" --quiet --controller adrc --iterations "$n" --duration 4s)
until "$netmc" status "$long" "${server[@]}" | grep -q "running  *[1-9][0-9]*/$n"; do sleep 0.1; done
# A watcher from any connection: what it is shown is what the store must hold after a restart.
watch_code=0
"$netmc" watch "$long" "${server[@]}" --quiet --json "$tmp/watched.json" >"$tmp/watch.txt" 2>&1 &
watch_pid=$!

# The disk fills up while the job runs.
dd if=/dev/zero of="$state/filler" bs=64k 2>/dev/null || true
df -h "$state" | tail -1
refused=0
"$netmc" submit "${server[@]}" --quiet --controller adrc --iterations 2 >"$tmp/full.txt" 2>&1 || refused=$?
cat "$tmp/full.txt"
[ "$refused" -ne 0 ] && grep -q "not accepted: job store .*jobs.sqlite: .*full.*accepts no job until its job store can be written" \
  "$tmp/full.txt" || { echo "FAIL: a submit to a full store was not refused with the reason"; exit 1; }
kill -0 "$server_pid" || { echo "FAIL: the server died on a full disk"; exit 1; }
# The running job's iterations can no longer be written; the job runs on to its last iteration,
# and its end waits to be kept: its watcher is not told of what the store does not hold.
until "$netmc" status "$long" "${server[@]}" | grep -q "^ *$long  *[a-z]*  *$n/$n"; do sleep 0.2; done
sleep 1
"$netmc" status "$long" "${server[@]}" | tail -1
"$netmc" status "$long" "${server[@]}" | grep -q "^ *$long  *running  *$n/$n .*waits for its end (done) to be written to the job store.*full" ||
  { echo "FAIL: the job's end was told before it was kept, or its status does not say why it waits"; exit 1; }
kill -0 "$watch_pid" 2>/dev/null || { echo "FAIL: the watcher was told of an end the store does not hold"; cat "$tmp/watch.txt"; exit 1; }
grep "not written" "$tmp/server.log" | head -2
failures=$(grep -c "not written" "$tmp/server.log")
[ "$failures" -le 3 ] || { echo "FAIL: the store logged $failures failures, not each once"; exit 1; }
echo "disk full: job $long ran $n/$n, its end waits to be kept; the watcher waits too; $failures failure(s) logged"
integrity "on the full disk"

# Room again: the waiting writes are kept (within the longest backoff, 2 s), then told.
rm -f "$state/filler"
room_ms=$(date +%s%3N)
wait "$watch_pid" || watch_code=$?
told_ms=$(date +%s%3N)
[ "$watch_code" -eq 0 ] || { echo "FAIL: the watcher of job $long did not see it done (exit $watch_code)"; cat "$tmp/watch.txt"; exit 1; }
grep "written again" "$tmp/server.log" | head -1
grep -q "written again after" "$tmp/server.log" || { echo "FAIL: the store's recovery was not logged"; exit 1; }
echo "room again: the watcher was told done $((told_ms - room_ms)) ms later"
again=$("$netmc" submit "${server[@]}" --quiet --controller adrc --iterations 2)
until "$netmc" status "$again" "${server[@]}" | grep -q "^ *$again  *done"; do sleep 0.1; done
[ "$(sqlite3 -readonly "$state/jobs.sqlite" "SELECT state FROM jobs WHERE id = $again")" = done ] ||
  { echo "FAIL: the job accepted after the disk had room again is not kept"; exit 1; }
echo "room again: job $again accepted, run and kept"

# A restart: the store's history of job $long is what its watcher saw (done, all its iterations, no
# error), from the server (netmc jobs, netmc watch) and from the store itself (--state-dir).
kill -TERM "$server_pid"
wait "$server_pid" || true
start server2 "$netmc_server" --listen "127.0.0.1:$port" --domain "$domain" --transport udp --state-dir "$state"
server_pid=${pids[-1]}
until grep -q "listening on 127.0.0.1:$port" "$tmp/server2.log"; do
  kill -0 "$server_pid" || { echo "FAIL: the server did not restart"; cat "$tmp/server2.log"; exit 1; }
  sleep 0.1
done
"$netmc" jobs "${server[@]}" --json >"$tmp/jobs.json"
"$netmc" jobs --state-dir "$state" --json >"$tmp/jobs-offline.json"
"$netmc" watch "$long" "${server[@]}" --quiet --json "$tmp/rewatched.json" >/dev/null
/usr/bin/python3 - "$tmp" "$long" "$n" <<'PY' ||
import json, sys
tmp, job, iterations = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
watched = json.load(open(f"{tmp}/watched.json"))
seen = len(watched["runs"][0]["iterations"]) if "runs" in watched else None
bad = []
for name in ("jobs.json", "jobs-offline.json"):
    record = next(j for j in json.load(open(f"{tmp}/{name}"))["jobs"] if int(j["job_id"]) == job)
    told = {"state": "done", "error": "", "iterations_done": seen}
    kept = {"state": record.get("state"), "error": record.get("error", ""), "iterations_done": record.get("iterations_done")}
    print(f"{name}: {kept}; the watcher saw {told}")
    if kept != told: bad.append(name)
sys.exit(1 if bad or seen != iterations else 0)
PY
  { echo "FAIL: after a restart the store's history of job $long is not what its watcher saw"; exit 1; }
cmp -s "$tmp/watched.json" "$tmp/rewatched.json" ||
  { echo "FAIL: netmc watch --json of job $long after the restart differs from what its watcher saw"; exit 1; }
echo "restart: job $long done $n/$n in netmc jobs, netmc jobs --state-dir and netmc watch --json, as its watcher saw"

# A store that is read-only (a disk mounted so; an open database keeps its mount writable, so the
# server stops first): a server started on it says why and exits 2.
kill -TERM "$server_pid"
wait "$server_pid" || true
mount -o remount,ro "$state"
integrity "on the read-only store"
# A server started on it says why and exits 2.
code=0
"$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp --state-dir "$state" \
  >"$tmp/readonly-start.txt" 2>&1 || code=$?
tail -1 "$tmp/readonly-start.txt"
[ "$code" -eq 2 ] && grep -q "state-dir: .*jobs.sqlite" "$tmp/readonly-start.txt" ||
  { echo "FAIL: a server started on a read-only store (exit $code) did not say why"; exit 1; }
mount -o remount,rw "$state"
echo "job store on a full and a read-only disk: refused with reasons, never corrupt"
