#!/usr/bin/env bash
# Node health on loopback, for each clock mode: a second node for a held axis (or a taken name)
# is refused on both sides; a killed node is gone from `netmc nodes` within the stated bound
# (status every 0.5 s, forgotten after 2.5 s of silence); restarted, it is back and the first
# job after the restart works.
# Usage: node_health.sh BUILD_DIR lockstep|realtime
source "$(dirname "$0")/lib.sh" "$@"
clock=${2:-lockstep}
source "$(dirname "$0")/lab.sh"
axis_bin=$netmc_axis
node() { "$axis_bin" --clock "$clock" --domain "$domain" --transport udp "$@"; }
bound_ms=3500   # docs/operations/distributed-runs.md: a dead node leaves the list within 3.5 s

lab_start x - -- "$axis_bin" --clock "$clock" --domain "$domain" --transport udp --node hx --axes x
lab_start y - -- "$axis_bin" --clock "$clock" --domain "$domain" --transport udp --node hy --axes y
lab_start server - -- "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
lab_wait_log server 'listening on' 10
port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/server.log")
lab_wait_log x 'serving' 10
lab_wait_log y 'serving' 10

# A rival for axis x, and one that takes the name hy: both refuse themselves (exit 3).
for rival in "--node dup --axes x" "--node hy --axes z"; do
  set +e
  # shellcheck disable=SC2086 # the words of $rival are flags
  node $rival >"$tmp/rival.log" 2>&1
  rc=$?
  set -e
  echo "rival ($rival): exit $rc: $(tail -n 1 "$tmp/rival.log")"
  [ "$rc" -eq 3 ] || { echo "FAIL: the rival was not refused"; exit 1; }
done
grep -q "node dup .* refused: axis x is held by node hx" "$tmp/server.log" &&
  grep -q "node hy .* refused: the name hy is taken" "$tmp/server.log" ||
  { echo "FAIL: the server did not log both refusals"; cat "$tmp/server.log"; exit 1; }
grep 'refused' "$tmp/server.log" | sed 's/^/server log: /'
"$netmc" nodes --server "127.0.0.1:$port" | grep -q '^hy ' || { echo "FAIL: the rival removed hy"; exit 1; }

listed() { "$netmc" nodes --server "127.0.0.1:$port" --json | grep -c "\"node\": *\"$1\"" || true; }
study=(--clock "$clock" --controller adrc+ilccc --iterations 2)
[ "$clock" = realtime ] && study+=(--duration 1s)

# Kill y (no goodbye) and time how long it stays listed.
lab_kill y KILL
killed=$(lab__now_ms)
while [ "$(listed hy)" -ne 0 ]; do
  [ $(( $(lab__now_ms) - killed )) -lt 10000 ] || break
  sleep 0.05
done
gone_ms=$(( $(lab__now_ms) - killed ))
echo "killed node hy: gone from netmc nodes after $gone_ms ms (bound $bound_ms ms)"
[ "$gone_ms" -le "$bound_ms" ] || { echo "FAIL: the dead node stayed listed"; exit 1; }

# Restart it under the same name: listed again, and the very next job works.
lab_start y2 - -- "$axis_bin" --clock "$clock" --domain "$domain" --transport udp --node hy --axes y
started=$(lab__now_ms)
while [ "$(listed hy)" -eq 0 ]; do
  [ $(( $(lab__now_ms) - started )) -lt 10000 ] || { echo "FAIL: the restarted node is not listed"; exit 1; }
  sleep 0.05
done
echo "restarted node hy: listed after $(( $(lab__now_ms) - started )) ms"
"$netmc" run --server "127.0.0.1:$port" --quiet "${study[@]}" --json "$tmp/after.json" >/dev/null ||
  { echo "FAIL: the first job after the restart failed"; exit 1; }
echo "first $clock job after the restart: done"
if [ "$clock" = lockstep ]; then
  "$netmc" sim --quiet "${study[@]}" --json "$tmp/sim.json" >/dev/null
  cmp -s "$tmp/after.json" "$tmp/sim.json" || { echo "FAIL: differs from netmc sim"; exit 1; }
  echo "and equals netmc sim byte for byte"
fi
