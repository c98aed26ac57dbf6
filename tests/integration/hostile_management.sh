#!/usr/bin/env bash
# A hostile client of the management endpoint (tests/integration/hostile_client.cpp) against a
# netmc-server with a token and a connection cap, two lockstep axis nodes on loopback: every
# attack is refused or contained (memory of answers never read, silent connections: issue 26),
# the server's log says why, and it still serves afterwards.
# Usage: hostile_management.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"

token="$tmp/token"
(umask 077 && head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$token")
export NETMC_TOKEN_FILE=$token

start x "$netmc_axis" --node it-x --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node it-y --axes y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --max-connections 8 --token-file "$token"
server_pid=${pids[-1]}
port=$(server_port 127.0.0.1)

# unread: 623 k status requests never read back, the server's VmRSS bound 200 MiB (issue 26: 2.9 GB);
# silent: 79 silent connections (127.0.0.1 and 127.0.0.2-40), the token's holder still answered.
"$build/tests/integration/netmc_hostile_client" --server "127.0.0.1:$port" --max-connections 8 \
  --server-pid "$server_pid" --rss-bound 200 --authentication-timeout 5 \
  files values cancel disconnect watch connections token unread silent

grep -q "closed: not authenticated within 5000 ms" "$tmp/server.log" ||
  { echo "FAIL: the server's log does not say why it closed the silent connections"; exit 1; }

grep -q "cancelled: its client disconnected" "$tmp/server.log" ||
  { echo "FAIL: the server's log does not say why the job of the vanished client ended"; exit 1; }
echo "server log: $(grep -m1 'its client disconnected' "$tmp/server.log")"
# Still serving: a job after the attacks runs to the end.
"$netmc" run --server "127.0.0.1:$port" --quiet --controller adrc --iterations 1 --duration 1s >/dev/null
echo "the server still runs jobs after the attacks"
