#!/usr/bin/env bash
# Self-test of lab.sh without netmc binaries: two namespace hosts reach each other over UDP and
# multicast, nftables loss drops about the asked share of UDP and no TCP, a time namespace shifts
# CLOCK_MONOTONIC, lab_stop/cleanup stop process trees (also SIGTERM-ignoring and escaped ones),
# assert_loopback_only accepts loopback binds and rejects wildcard, TCP-wildcard and multicast binds.
# Needs root, iproute2, nftables, time namespaces and python3; exits 77 (skipped) otherwise.
# Usage: lab_selftest.sh
source "$(dirname "$0")/lib.sh" "$@"
source "$here/lab.sh"

command -v python3 >/dev/null || { echo "skipped: python3 is not installed"; exit 77; }
py=$(python3 -c 'import sys; print(sys.executable)')   # not a pyenv shim: faster, one process
lab_init
lab_need_nft
lab_need_timens
fail() { echo "FAIL: $*"; exit 1; }

lab_host a
lab_host b
A=$(lab_addr a)
B=$(lab_addr b)
[ "$A" = "$lab_net.1" ] && [ "$B" = "$lab_net.2" ] || fail "addresses $A $B"
ip -n "$(lab_ns a)" route show 224.0.0.0/4 | grep -q 'dev eth0' || fail "no multicast route"
echo "hosts a=$A b=$B (namespaces $(lab_ns a), $(lab_ns b))"

# UDP echo server on b; python one-liners for everything else.
echo_srv='
import socket, sys
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind((sys.argv[1], int(sys.argv[2])))
print("ready", flush=True)
while True:
    d, a = s.recvfrom(2048); s.sendto(d, a)'
# ping ADDR PORT N TIMEOUT: sends N datagrams one by one, prints how many echoes came back.
ping='
import socket, sys
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.settimeout(float(sys.argv[4])); ok = 0
for i in range(int(sys.argv[3])):
    s.sendto(b"ping%d" % i, (sys.argv[1], int(sys.argv[2])))
    try:
        while s.recv(2048) != b"ping%d" % i: pass
        ok += 1
    except socket.timeout: pass
print(ok)'
lab_start echo b -- "$py" -c "$echo_srv" "$B" 5000
lab_wait_log echo '^ready'
n=$(lab_exec a -- "$py" -c "$ping" "$B" 5000 5 1)
[ "$n" = 5 ] || fail "a -> b -> a UDP: $n of 5 echoes"
echo "UDP a -> b -> a: 5 of 5 echoes"

# Multicast a -> b over the 224.0.0.0/4 route (as DDS discovery does).
mc_recv='
import socket, struct, sys
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
s.bind(("239.255.77.1", 5001))
s.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, struct.pack("4s4s", socket.inet_aton("239.255.77.1"), socket.inet_aton(sys.argv[1])))
print("ready", flush=True); s.settimeout(3)
print("got", s.recv(100).decode(), flush=True)'
lab_start mc b -- "$py" -c "$mc_recv" "$B"
lab_wait_log mc '^ready'
lab_exec a -- "$py" -c '
import socket, time
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 1)
for _ in range(20):
    s.sendto(b"hello", ("239.255.77.1", 5001)); time.sleep(0.05)'
lab_wait mc 5 || fail "multicast receiver: $(cat "$tmp/mc.log")"
grep -q '^got hello' "$tmp/mc.log" || fail "multicast a -> b"
echo "multicast a -> 239.255.77.1 -> b: received"

# 100 % loss on a: UDP blocked, TCP unaffected (and not counted by the nft rule).
tcp_echo='
import socket, sys
s = socket.socket(); s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1); s.bind((sys.argv[1], 5002)); s.listen(1)
print("ready", flush=True)
c, _ = s.accept()
while True:
    d = c.recv(65536)
    if not d: break
    c.sendall(d)'
lab_start tcp b -- "$py" -c "$tcp_echo" "$B"
lab_wait_log tcp '^ready'
lab_loss a 100
n=$(lab_exec a -- "$py" -c "$ping" "$B" 5000 3 0.3)
[ "$n" = 0 ] || fail "UDP went through 100 % loss ($n of 3)"
dropped=$(lab_loss_dropped a)
[ "$dropped" = 3 ] || fail "nft counted $dropped drops, expected 3"
lab_exec a -- timeout 5 "$py" -c '
import socket, sys
c = socket.create_connection((sys.argv[1], 5002), timeout=3); data = bytes(range(256)) * 4096
c.sendall(data); c.shutdown(socket.SHUT_WR); got = b""
while len(got) < len(data):
    d = c.recv(65536)
    if not d: break
    got += d
sys.exit(0 if got == data else 1)' "$B" || fail "TCP through UDP loss"
[ "$(lab_loss_dropped a)" = 3 ] || fail "nft dropped TCP segments"
lab_wait tcp 5 || fail "tcp echo server did not end"
echo "100 % UDP loss on a: 0 of 3 UDP echoes, 3 drops counted; 1 MiB TCP echo intact"

# measure HOST DIRECTION COUNT SIZE: COUNT datagrams of SIZE bytes a -> b through lab_loss 20 %;
# sets received and dropped. (Runs in the main shell: lab_start state lives in shell variables.)
count_srv='
import socket, sys
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.setsockopt(socket.SOL_SOCKET, 33, 1 << 23)  # SO_RCVBUFFORCE
s.bind((sys.argv[1], 5003)); print("ready", flush=True); s.settimeout(10); n = 0
try:
    s.recv(9000); n = 1; s.settimeout(0.5)
    while True: s.recv(9000); n += 1
except socket.timeout: pass
print("count", n, flush=True)'
measure() {
  local where=$1 dir=$2 count=$3 size=$4 log=count_$1_$2_$4
  lab_loss "$where" 20 "$dir"
  lab_start "$log" b -- "$py" -c "$count_srv" "$B"
  lab_wait_log "$log" '^ready'
  lab_exec a -- "$py" -c '
import socket, sys, time
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
for i in range(int(sys.argv[2])):
    s.sendto(b"x" * int(sys.argv[3]), (sys.argv[1], 5003))
    if i % 50 == 49: time.sleep(0.002)' "$B" "$count" "$size"
  lab_wait "$log" 15
  received=$(awk '/^count/ {print $2}' "$tmp/$log.log")
  dropped=$(lab_loss_dropped "$where")
  lab_loss "$where" 0
}
# HOST DIRECTION COUNT SIZE: 64-byte datagrams a -> b lost on a's way out, on b's way in, and
# 4000-byte datagrams (3 IPv4 fragments at MTU 1500: lost as a whole, so still ~20 %, not ~49 %).
for run in "a out 2000 64" "b in 2000 64" "a out 500 4000"; do
  read -r where dir count size <<<"$run"
  measure "$where" "$dir" "$count" "$size"
  lost=$((count - received))
  pct=$((lost * 1000 / count))
  echo "20 % loss ($dir on $where, ${size}-byte datagrams): $received of $count received," \
    "$lost lost ($((pct / 10)).$((pct % 10)) %), nft dropped $dropped"
  [ "$lost" -eq "$dropped" ] || fail "losses other than nft's: lost $lost, dropped $dropped"
  [ "$pct" -ge 120 ] && [ "$pct" -le 280 ] || fail "loss rate outside 12-28 %"
done
tables=$(ip netns exec "$lab_tag-bridge" nft list tables)
[ -z "$tables" ] || fail "lab_loss 0 left nft tables: $tables"
n=$(lab_exec a -- "$py" -c "$ping" "$B" 5000 5 1)
[ "$n" = 5 ] || fail "after lab_loss 0: $n of 5 echoes"
echo "lab_loss 0: nft tables removed, 5 of 5 echoes"

# Time namespaces: CLOCK_MONOTONIC + 86400 s and - 5 s; an impossible offset is refused clearly.
mono='import time; print(time.clock_gettime(time.CLOCK_MONOTONIC))'
before=$("$py" -c "$mono")
lab_start mono b --monotonic 86400 -- "$py" -c "$mono"
lab_wait mono 10
after=$("$py" -c "$mono")
inner=$(cat "$tmp/mono.log")
"$py" -c 'import sys; b, i, a = map(float, sys.argv[1:]); sys.exit(0 if b + 86400 <= i <= a + 86400 else 1)' \
  "$before" "$inner" "$after" || fail "monotonic in time namespace $inner, host $before .. $after"
echo "--monotonic 86400: host $before .. $after s, inside $inner s"
before=$("$py" -c "$mono")
lab_start mono_neg a --monotonic -5 -- "$py" -c "$mono"
lab_wait mono_neg 10
after=$("$py" -c "$mono")
inner=$(cat "$tmp/mono_neg.log")
"$py" -c 'import sys; b, i, a = map(float, sys.argv[1:]); sys.exit(0 if b - 5 <= i <= a - 5 else 1)' \
  "$before" "$inner" "$after" || fail "monotonic -5: $inner, host $before .. $after"
echo "--monotonic -5: inside $inner s"
if lab_start bad a --monotonic -1000000000 -- true 2>"$tmp/bad.err"; then fail "offset -1e9 accepted"; fi
grep -q "must be >=" "$tmp/bad.err" || fail "no clear message: $(cat "$tmp/bad.err")"
echo "--monotonic -1000000000 refused: $(head -c 200 "$tmp/bad.err")"

# Stopping: a process tree in a time namespace, a SIGTERM-ignoring one, one that leaves its session.
lab_start tree a --monotonic 100 -- bash -c 'sleep 1000 & sleep 1000 & wait'
lab_start stubborn b -- bash -c 'trap "" TERM; sleep 1000 & wait'
lab_start escape a -- bash -c 'setsid sleep 999 & exec sleep 1000'
sleep 0.3
tree=$(lab_pids tree | tr '\n' ' ')
[ "$(wc -w <<<"$tree")" -eq 4 ] || fail "tree: expected unshare, bash and 2 sleeps: $tree"
stubborn=$(lab_pids stubborn | tr '\n' ' ')
escaped=$(ip netns pids "$(lab_ns a)" | while read -r p; do
  if [ "$(ps -o args= -p "$p")" = "sleep 999" ]; then echo "$p"; fi; done)
[ -n "$escaped" ] || fail "no escaped sleep 999 found"
lab__leftovers | grep -qx "$escaped" || fail "leftover detection misses the escaped process"
lab_stop tree
[ "$(lab_status tree)" = 143 ] || fail "tree status $(lab_status tree)"
for p in $tree; do ! lab__alive "$p" || fail "tree process $p still alive"; done
t0=$(date +%s%N)
LAB_STOP_GRACE=1 lab_stop stubborn 2>"$tmp/stubborn.err"
t1=$(date +%s%N)
grep -q SIGKILL "$tmp/stubborn.err" || fail "no SIGKILL message"
[ "$(lab_status stubborn)" = 137 ] || fail "stubborn status $(lab_status stubborn)"
for p in $stubborn; do ! lab__alive "$p" || fail "stubborn process $p still alive"; done
echo "lab_stop: tree of 4 (unshare, bash, 2 sleeps) ended by SIGTERM (status 143);" \
  "SIGTERM-ignoring pair SIGKILLed after $(((t1 - t0) / 1000000)) ms (status 137)"

# A name is taken again only once its session is over (a restarted server).
lab_start again - -- sleep 1000
if lab_start again - -- true 2>"$tmp/again.err"; then fail "a running name was started again"; fi
grep -q "again is still running" "$tmp/again.err" || fail "no clear message: $(cat "$tmp/again.err")"
first=$(lab_pid again)
lab_stop again
lab_start again - -- sh -c 'echo second'
lab_wait again 10
[ "$(lab_pid again)" != "$first" ] && [ "$(lab_status again)" = 0 ] && [ "$(cat "$tmp/again.log")" = second ] ||
  fail "the name again did not start anew: pid $(lab_pid again), status $(lab_status again)"
echo "lab_start: a running name refused, the same name started again once it ended"

# assert_loopback_only on the machine's own namespace, with processes named labfake-* (not netmc-*,
# which a concurrent netmc test's assert_loopback_only 'netmc' would see).
fake='
import socket, sys, time
open("/proc/self/comm", "w").write(sys.argv[1])
fam = socket.AF_INET6 if ":" in sys.argv[3] else socket.AF_INET
s = socket.socket(fam, socket.SOCK_STREAM if sys.argv[2] == "tcp" else socket.SOCK_DGRAM)
s.bind((sys.argv[3], 0))
if sys.argv[2] == "tcp": s.listen(1)
print("ready", flush=True); time.sleep(60)'
start_fake() { lab_start "$1" - -- "$py" -c "$fake" "$@"; lab_wait_log "$1" '^ready'; }
start_fake labfake-lo udp 127.0.0.1
start_fake labfake-lot tcp 127.0.0.2
ss -H -uanp | grep -q '"labfake-lo",pid=' || fail "ss does not show the name labfake-lo"
assert_loopback_only '^labfake-lot?$' || fail "loopback binds rejected"
if "$py" -c 'import socket; socket.socket(socket.AF_INET6).bind(("::1", 0))' 2>/dev/null; then
  start_fake labfake-lo6 udp ::1
  assert_loopback_only '^labfake-lo6$' || fail "::1 rejected"
fi
expect_reject() {   # PATTERN TEXT: assert_loopback_only must fail and say TEXT
  if assert_loopback_only "$1" 2>"$tmp/assert.err"; then fail "assert_loopback_only '$1' passed"; fi
  grep -q "$2" "$tmp/assert.err" || fail "assert_loopback_only '$1': $(cat "$tmp/assert.err")"
  echo "rejected /$1/: $(grep -m1 -e '^  ' -e 'no UDP' "$tmp/assert.err" | sed 's/^ *//' | cut -c1-100)"
}
start_fake labfake-any udp 0.0.0.0
start_fake labfake-anyt tcp 0.0.0.0
start_fake labfake-mcast udp 239.255.77.9
expect_reject '^labfake-any$' 'udp 0.0.0.0:[0-9]*: wildcard'
expect_reject '^labfake-anyt$' 'tcp 0.0.0.0:[0-9]*: wildcard'
expect_reject '^labfake-mcast$' 'multicast group'
expect_reject '^labfake-none$' 'no UDP/TCP socket'
if assert_loopback_only '^labfake-' 2>/dev/null; then fail "mixed set passed"; fi

# Explicit cleanup: the escaped process is found and killed, namespaces go; the EXIT trap repeats it.
namespaces=("$(lab_ns a)" "$(lab_ns b)" "$lab_tag-bridge")
lab_cleanup 2>"$tmp/cleanup.err" || { cat "$tmp/cleanup.err"; fail "lab_cleanup"; }
grep -q "processes still in namespace" "$tmp/cleanup.err" || fail "escapee not reported"
! lab__alive "$escaped" || fail "escaped process $escaped survived"
for ns in "${namespaces[@]}"; do [ ! -e "/run/netns/$ns" ] || fail "namespace $ns left"; done
[ -z "$(lab__leftovers)" ] || fail "leftovers after cleanup"
echo "lab_cleanup: escaped process killed, 3 namespaces deleted, nothing left"
echo "lab self-test passed"
