#!/usr/bin/env bash
# Separate hosts: netmc-server and each netmc-axis in its own Linux network namespace, joined by
# veth pairs on a bridge (own addresses 10.77.0.0/24, reachable only inside these namespaces).
# The paper-001 job runs across them over UDP (lockstep) and must equal `netmc sim`; the client
# reaches the server's management endpoint over TCP from another namespace.
# Needs root and `ip netns`; exits 77 (skipped) where that is not permitted.
# Usage: separate_hosts.sh BUILD_DIR [extra study flags...]
set -euo pipefail
trap 'echo "$0: failed at line $LINENO (exit $?)"' ERR
build=$(cd "$1" && pwd)
shift
if [ "$(id -u)" -ne 0 ] || ! command -v ip >/dev/null; then
  echo "skipped: separate-hosts test needs root and iproute2"; exit 77
fi
tag=nm$$
bridge_ns=${tag}br
hosts=(srv ax ay)
if ! ip netns add "$bridge_ns" 2>/dev/null; then
  echo "skipped: creating network namespaces is not permitted here"; exit 77
fi
source "$(dirname "$0")/lib.sh"
extra_cleanup+=('for h in "${hosts[@]}"; do ip netns del "$tag$h" 2>/dev/null; done'
                'ip netns del "$bridge_ns" 2>/dev/null')

ip -n "$bridge_ns" link add br0 type bridge
ip -n "$bridge_ns" link set br0 up
address=1
for h in "${hosts[@]}"; do
  ns=$tag$h
  ip netns add "$ns"
  ip link add "v$tag$h" type veth peer name eth0 netns "$ns"
  ip link set "v$tag$h" netns "$bridge_ns"
  ip -n "$bridge_ns" link set "v$tag$h" master br0 up
  ip -n "$ns" addr add "10.77.0.$address/24" dev eth0
  ip -n "$ns" link set eth0 up
  ip -n "$ns" link set lo up
  ip -n "$ns" route add 224.0.0.0/4 dev eth0   # DDS discovery multicast
  address=$((address + 1))
done

run_in() { local ns=$tag$1; shift; ip netns exec "$ns" "$@"; }
start x run_in ax "$build/server/axis/netmc-axis" --node host-x --axes x --transport udp
start y run_in ay "$build/server/axis/netmc-axis" --node host-y --axes y --transport udp
start server run_in srv "$build/server/service/netmc-server" --listen 10.77.0.1:0 --transport udp
port=$(server_port 10.77.0.1)

run_in ay "$build/client/netmc" nodes --server "10.77.0.1:$port"
run_in ay "$build/client/netmc" run --server "10.77.0.1:$port" --quiet --json "$tmp/dds.json" "$@" >"$tmp/dds.txt"
"$build/client/netmc" sim --json "$tmp/sim.json" "$@" >/dev/null
cat "$tmp/dds.txt"
if cmp -s "$tmp/dds.json" "$tmp/sim.json"; then
  echo "separate hosts (network namespaces, UDP): identical JSON to netmc sim"
else
  echo "separate hosts differ from netmc sim:"; diff "$tmp/sim.json" "$tmp/dds.json" | head -20; exit 1
fi
