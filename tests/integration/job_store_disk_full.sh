#!/usr/bin/env bash
# The job store on a full disk and on a read-only one (a tmpfs of 3 MiB in a mount namespace of
# the test's own): the server refuses new jobs with a message that says why, the job that runs
# goes on to its end, the store's integrity check passes, jobs are accepted again once there is
# room; a server started on a read-only store says why and exits.
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
long=$("$netmc" submit "${server[@]}" --quiet --controller adrc --iterations 300 --duration 4s)
until "$netmc" status "$long" "${server[@]}" | grep -q "running  *[1-9][0-9]*/300"; do sleep 0.1; done

# The disk fills up while the job runs.
dd if=/dev/zero of="$state/filler" bs=64k 2>/dev/null || true
df -h "$state" | tail -1
refused=0
"$netmc" submit "${server[@]}" --quiet --controller adrc --iterations 2 >"$tmp/full.txt" 2>&1 || refused=$?
cat "$tmp/full.txt"
[ "$refused" -ne 0 ] && grep -q "not accepted: job store .*jobs.sqlite: .*full.*accepts no job until its job store can be written" \
  "$tmp/full.txt" || { echo "FAIL: a submit to a full store was not refused with the reason"; exit 1; }
kill -0 "$server_pid" || { echo "FAIL: the server died on a full disk"; exit 1; }
# The running job's iterations can no longer be written; the job runs on to its end.
until "$netmc" status "$long" "${server[@]}" | grep -q "^ *$long  *\(done\|failed\|cancelled\)"; do sleep 0.2; done
"$netmc" status "$long" "${server[@]}" | grep -q "^ *$long  *done  *300/300" ||
  { echo "FAIL: the job running when the disk filled did not end done"; "$netmc" status "${server[@]}"; exit 1; }
grep "not written" "$tmp/server.log" | head -2
integrity "on the full disk"

# Room again: accepted and kept.
rm -f "$state/filler"
again=$("$netmc" submit "${server[@]}" --quiet --controller adrc --iterations 2)
until "$netmc" status "$again" "${server[@]}" | grep -q "^ *$again  *done"; do sleep 0.1; done
sleep 0.5  # its end is written after it is told
[ "$(sqlite3 -readonly "$state/jobs.sqlite" "SELECT state FROM jobs WHERE id = $again")" = done ] ||
  { echo "FAIL: the job accepted after the disk had room again is not kept"; exit 1; }
echo "room again: job $again accepted, run and kept"

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
