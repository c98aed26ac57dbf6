#!/usr/bin/env bash
# The server's memory with jobs that carry large specs (450 000-sample inline delay traces,
# 3.6 MB each, near the 4 MiB an axis node takes; a spec beyond is refused at submit): an ended
# job keeps its status and result, not its spec, so 30 such jobs run one after another leave the
# server's RSS where it was; jobs waiting in the queue may hold at most 256 MiB of specs, and a
# submit beyond is refused with the reason.
# Usage: server_memory.sh BUILD_DIR   (loopback only)
source "$(dirname "$0")/lib.sh" "$@"
rss_mib() { awk '/^VmRSS/ { printf "%d", $2 / 1024 }' "/proc/$1/status"; }

start x "$netmc_axis" --node mem-x --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node mem-y --axes y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
server_pid=${pids[-1]}
port=$(server_port 127.0.0.1)
server=(--server "127.0.0.1:$port")
/usr/bin/python3 -c 'import sys; sys.stdout.write("0.0005\n" * 450000)' >"$tmp/trace.csv"
/usr/bin/python3 -c 'import sys; sys.stdout.write("0.0005\n" * 1000000)' >"$tmp/huge.csv"
big=(--controller adrc --iterations 1 --duration 0.2s --delay "trace:$tmp/trace.csv")

# 8 MB: more than an axis node takes; refused when submitted, not when it starts.
code=0
"$netmc" submit "${server[@]}" --quiet --controller adrc --iterations 1 --delay "trace:$tmp/huge.csv" \
  >"$tmp/huge.txt" 2>&1 || code=$?
cat "$tmp/huge.txt"
[ "$code" -ne 0 ] && grep -q "submit: the job spec takes 8[0-9]* bytes, more than the 4194304" "$tmp/huge.txt" ||
  { echo "FAIL: a spec larger than the axes take was not refused at submit"; exit 1; }

"$netmc" run "${server[@]}" --quiet "${big[@]}" >/dev/null
before=$(rss_mib "$server_pid")
for _ in $(seq 30); do "$netmc" run "${server[@]}" --quiet "${big[@]}" >/dev/null; done
after=$(rss_mib "$server_pid")
echo "server RSS after 1 job with a 3.6 MB spec: $before MiB; after 30 more: $after MiB"
[ "$after" -le $((before + 64)) ] || { echo "FAIL: 30 ended jobs grew the server by $((after - before)) MiB (bound 64)"; exit 1; }

# A long job holds the axes; big jobs queue behind it until their specs reach 256 MiB.
long=$("$netmc" submit "${server[@]}" --quiet --controller adrc --iterations 10000 --duration 4s)
until "$netmc" status "$long" "${server[@]}" | grep -q "running"; do sleep 0.1; done
queued=0
refused=""
for _ in $(seq 100); do
  if "$netmc" submit "${server[@]}" --quiet "${big[@]}" >/dev/null 2>"$tmp/submit.err"; then
    queued=$((queued + 1))
  else
    refused=$(cat "$tmp/submit.err"); break
  fi
done
echo "queued $queued jobs of 3.6 MB; the next: $refused"
echo "$refused" | grep -q "the jobs waiting hold .* MiB of specs and this one .* beyond the server's 256 MiB" ||
  { echo "FAIL: the queue's specs are not bounded"; exit 1; }
[ "$queued" -ge 60 ] && [ "$queued" -le 75 ] || { echo "FAIL: $queued jobs of 3.6 MB queued (expected about 74)"; exit 1; }
full=$(rss_mib "$server_pid")
echo "server RSS with $queued jobs of 3.6 MB queued: $full MiB"
[ "$full" -le $((before + 400)) ] || { echo "FAIL: the server holds $full MiB with a full queue (bound $((before + 400)))"; exit 1; }
