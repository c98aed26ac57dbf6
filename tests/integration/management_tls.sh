#!/usr/bin/env bash
# The management endpoint over TLS, on loopback in lockstep: scripts/make-lab-pki.sh issues the
# endpoint's certificate for 127.0.0.1; netmc-server takes it (--tls-cert/--tls-key) with a token.
# A client trusting the lab CA (NETMC_TLS_CA) runs a job and gets the same JSON as netmc sim; a
# plain client is closed before any answer, with a message saying what to set, and the server's
# log names it; a client trusting another CA refuses the server. A second server asks for client
# certificates too (--tls-client-ca): it serves the lab's operator certificate and no other.
# Usage: management_tls.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
root=$(cd "$(dirname "$0")/../.." && pwd)

bash "$root/scripts/make-lab-pki.sh" "$tmp/pki" --server tls-server --management 127.0.0.1 \
  --management-client operator >/dev/null
bash "$root/scripts/make-lab-pki.sh" "$tmp/other" --server other --management 127.0.0.1 \
  --management-client operator >/dev/null
head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/token"
export NETMC_TOKEN_FILE=$tmp/token
start x "$netmc_axis" --node tx --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node ty --axes y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --token-file "$tmp/token" --tls-cert "$tmp/pki/management.pem" --tls-key "$tmp/pki/management.key"
port=$(server_port 127.0.0.1)
grep -q "($(printf 'TLS 1.3, certificate /CN=netmc management')" "$tmp/server.log" ||
  { echo "FAIL: the server's start line does not say TLS"; cat "$tmp/server.log"; exit 1; }
echo "server: $(grep -o 'listening on [^)]*)' "$tmp/server.log")"
server=(--server "127.0.0.1:$port")
job=(--quiet --controller adrc --iterations 2 --duration 2s)

# Trusting the lab CA: the job runs, and equals the in-process run.
NETMC_TLS_CA=$tmp/pki/ca.pem "$netmc" run "${server[@]}" "${job[@]}" --json "$tmp/tls.json" >/dev/null
"$netmc" sim "${job[@]}" --json "$tmp/sim.json" >/dev/null
same_json "$tmp/sim.json" "$tmp/tls.json" "netmc run over TLS"

# Without TLS: closed before any answer, and told what to set.
plain=0
"$netmc" status "${server[@]}" >"$tmp/plain.txt" 2>&1 || plain=$?
[ "$plain" -ne 0 ] && grep -q "speaks TLS only: set NETMC_TLS_CA" "$tmp/plain.txt" ||
  { echo "FAIL: a plain client of the TLS server"; cat "$tmp/plain.txt"; exit 1; }
echo "plain client: $(cat "$tmp/plain.txt")"
for _ in $(seq 20); do grep -q "TLS handshake failed" "$tmp/server.log" && break; sleep 0.05; done
echo "server log: $(grep -o 'management connection from .*' "$tmp/server.log" | head -1)"
grep -q "management connection from 127.0.0.1:[0-9]* closed: TLS handshake failed" "$tmp/server.log" ||
  { echo "FAIL: the server's log does not name the refused plain client"; exit 1; }

# Trusting another CA: the client refuses the server.
stranger=0
NETMC_TLS_CA=$tmp/other/ca.pem "$netmc" status "${server[@]}" >"$tmp/stranger.txt" 2>&1 || stranger=$?
[ "$stranger" -ne 0 ] && grep -q "TLS handshake failed: certificate verify failed" "$tmp/stranger.txt" ||
  { echo "FAIL: a client of another CA trusted the server"; cat "$tmp/stranger.txt"; exit 1; }
echo "client trusting another CA: $(cat "$tmp/stranger.txt")"

# Client certificates: only the lab's operator is served.
start server2 "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --token-file "$tmp/token" --tls-cert "$tmp/pki/management.pem" --tls-key "$tmp/pki/management.key" \
  --tls-client-ca "$tmp/pki/ca.pem"
port2=""
for _ in $(seq 100); do
  port2=$(sed -n "s/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p" "$tmp/server2.log")
  [ -n "$port2" ] && break
  sleep 0.1
done
grep -q "clients need a certificate of the client CA" "$tmp/server2.log" ||
  { echo "FAIL: the second server's start line does not say it asks for client certificates"; cat "$tmp/server2.log"; exit 1; }
export NETMC_TLS_CA=$tmp/pki/ca.pem
nocert=0
"$netmc" status --server "127.0.0.1:$port2" >"$tmp/nocert.txt" 2>&1 || nocert=$?
[ "$nocert" -ne 0 ] && grep -q "certificate required (a server started with --tls-client-ca" "$tmp/nocert.txt" ||
  { echo "FAIL: a client without a certificate"; cat "$tmp/nocert.txt"; exit 1; }
echo "client without a certificate: $(cat "$tmp/nocert.txt")"
foreign=0
NETMC_TLS_CERT=$tmp/other/operator.pem NETMC_TLS_KEY=$tmp/other/operator.key \
  "$netmc" status --server "127.0.0.1:$port2" >"$tmp/foreign.txt" 2>&1 || foreign=$?
[ "$foreign" -ne 0 ] && grep -q "TLS connection ended: tlsv1 alert unknown ca" "$tmp/foreign.txt" ||
  { echo "FAIL: a client certificate of another CA"; cat "$tmp/foreign.txt"; exit 1; }
echo "client certificate of another CA: $(cat "$tmp/foreign.txt")"
NETMC_TLS_CERT=$tmp/pki/operator.pem NETMC_TLS_KEY=$tmp/pki/operator.key \
  "$netmc" run --server "127.0.0.1:$port2" "${job[@]}" --json "$tmp/mtls.json" >/dev/null
same_json "$tmp/sim.json" "$tmp/mtls.json" "netmc run with the operator's client certificate"
