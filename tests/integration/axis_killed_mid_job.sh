#!/usr/bin/env bash
# An axis process killed mid-job: the server fails the job with a clear error naming the axis,
# the client exits non-zero with that message, the server and the other axis stay up.
# Usage: axis_killed_mid_job.sh BUILD_DIR [lockstep|realtime]
# Realtime: the server must notice within a few periods (--axis-silence 50 ms: 10 periods at h = 5 ms).
source "$(dirname "$0")/lib.sh" "$@"
clock=${2:-lockstep}

start x "$netmc_axis" --node kill-x --axes x --clock "$clock" --domain "$domain" --transport udp
x_pid=${pids[-1]}
start y "$netmc_axis" --node kill-y --axes y --clock "$clock" --domain "$domain" --transport udp
y_pid=${pids[-1]}
start server "$netmc_server" --listen 127.0.0.1:0 --axis-timeout 1000 \
  --axis-silence 50 --domain "$domain" --transport udp
server_pid=${pids[-1]}
port=$(server_port 127.0.0.1)
# Both nodes serving (each listens 1.5 s for a rival first), so the kill lands mid-job.
for _ in $(seq 100); do
  grep -q serving "$tmp/x.log" && grep -q serving "$tmp/y.log" && break
  sleep 0.1
done

( sleep 2; kill -9 "$y_pid"; date +%s%3N >"$tmp/killed_at" ) &
set +e
"$netmc" run --server "127.0.0.1:$port" --clock "$clock" --controller adrc+ilccc --iterations 200 \
  >"$tmp/run.out" 2>"$tmp/run.err"
rc=$?
set -e
end=$(date +%s%3N)
cat "$tmp/run.err" | tail -3
if [ "$rc" -eq 0 ]; then echo "FAIL: the job succeeded although axis y was killed"; exit 1; fi
grep -q "axis y" "$tmp/run.err" || { echo "FAIL: no error naming axis y"; exit 1; }
grep -q "job 1 failed: axis y" "$tmp/server.log" || { echo "FAIL: server log"; cat "$tmp/server.log"; exit 1; }
noticed_ms=$(( end - $(cat "$tmp/killed_at") ))
limit_ms=$([ "$clock" = realtime ] && echo 500 || echo 2500)
if [ "$noticed_ms" -gt "$limit_ms" ]; then echo "FAIL: noticed after $noticed_ms ms (limit $limit_ms)"; exit 1; fi
kill -0 "$server_pid" || { echo "FAIL: netmc-server died"; exit 1; }
kill -0 "$x_pid" || { echo "FAIL: the other axis died"; exit 1; }
"$netmc" nodes --server "127.0.0.1:$port" >/dev/null || { echo "FAIL: server no longer answers"; exit 1; }
echo "$clock: axis y killed; the client had the job's failure $noticed_ms ms later (exit code $rc); server and axis x still up"
