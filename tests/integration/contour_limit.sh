#!/usr/bin/env bash
# The job's contour-error limit, on loopback: two realtime nodes (simulated drives) and a server.
# adrc+pidccc behind a constant 30 ms downlink delay (beyond what its cross coupling takes) with
# --contour-error-limit 0.5mm: the job fails at the cycle the contour error crosses 0.5 mm, its
# message naming the error, the cycle and the axis; both axes are quick-stopped by the job's
# server (each node says so); `netmc sim` with the same flags stops the run at its crossing with
# the same kind of message; without the limit the same job runs on to the divergence limit.
# Usage: contour_limit.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"

for axis in x y; do
  start "$axis" "$netmc_axis" --node lim-$axis --axes $axis --clock realtime --domain "$domain" --transport udp
done
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
port=$(server_port 127.0.0.1)
study=(--controller adrc+pidccc --delay constant:30ms --iterations 1 --contour-error-limit 0.5mm)

failed=0
"$netmc" run --server "127.0.0.1:$port" --clock realtime "${study[@]}" --quiet >"$tmp/run.txt" 2>&1 || failed=$?
cat "$tmp/run.txt"
[ "$failed" -ne 0 ] || lab_fail "the job that crossed its contour-error limit did not fail"
grep -q 'contour error 0\.[5-9][0-9]* mm beyond the limit 0\.500 mm at cycle [0-9]* (t = [0-9.]* s); axis [xy] ' \
  "$tmp/run.txt" || lab_fail "the failure does not name the error, the cycle and the axis"
grep -q 'the axes were quick-stopped' "$tmp/run.txt" || lab_fail "the failure does not say the axes were quick-stopped"
cycle=$(grep -o 'at cycle [0-9]*' "$tmp/run.txt" | head -n 1 | awk '{print $3}')
for axis in x y; do
  lab_wait_log "$axis" 'quick stop by its job.s server' 5 || lab_fail "node lim-$axis did not quick-stop its axis"
done
echo "realtime: failed at cycle $cycle; both nodes quick-stopped their axes"

"$netmc" sim "${study[@]}" --quiet >"$tmp/sim.txt" 2>&1 || true
grep -q 'stopped: contour error 0\.[5-9][0-9]* mm beyond the limit 0\.500 mm at cycle [0-9]*' "$tmp/sim.txt" ||
  { cat "$tmp/sim.txt"; lab_fail "netmc sim did not stop at the limit"; }
echo "netmc sim: $(grep -o 'stopped: .*' "$tmp/sim.txt" | head -n 1)"
"$netmc" sim --controller adrc+pidccc --delay constant:30ms --iterations 1 --quiet >"$tmp/free.txt" 2>&1 || true
grep -q 'unstable' "$tmp/free.txt" && ! grep -q 'stopped:' "$tmp/free.txt" ||
  { cat "$tmp/free.txt"; lab_fail "without the limit the run did not go on to the divergence limit"; }
echo "without the limit: $(grep -o 'unstable.*' "$tmp/free.txt" | head -n 1)"
