#!/usr/bin/env bash
# Separate hosts: netmc-server, each netmc-axis and the client in network namespaces of their own
# (lab.sh: veth pairs on a bridge, private addresses reachable only inside them). Every DDS
# process is given its interface (--interface eth0). The paper-001 job runs across them over UDP
# (lockstep) and must equal `netmc sim`, first with multicast discovery, then through a Fast DDS
# Discovery Server (fast-discovery-server from fastdds-tools) with no multicast
# route at all.
# Usage: separate_hosts.sh BUILD_DIR [extra study flags...]
source "$(dirname "$0")/lib.sh" "$@"
shift
source "$(dirname "$0")/lab.sh"
lab_init
for h in srv ax ay cl ds; do lab_host "$h"; done
srv=$(lab_addr srv)
study=("$@")
"$netmc" sim --json "$tmp/sim.json" "${study[@]}" >/dev/null

# run_study TAG DDS_FLAGS...: axis nodes, server, and the study from the client host.
run_study() {
  local tag=$1 port
  shift
  lab_start "x$tag" ax -- "$netmc_axis" --node host-x --axes x --transport udp --interface eth0 "$@"
  lab_start "y$tag" ay -- "$netmc_axis" --node host-y --axes y --transport udp --interface eth0 "$@"
  lab_start "server$tag" srv -- "$netmc_server" --listen "$srv:0" --transport udp \
    --interface eth0 "$@"
  lab_wait_log "server$tag" 'listening on' 10
  lab_wait_log "x$tag" 'serving' 10
  lab_wait_log "y$tag" 'serving' 10
  port=$(sed -n "s/.*listening on $srv:\([0-9]*\).*/\1/p" "$tmp/server$tag.log")
  lab_exec cl -- "$netmc" nodes --server "$srv:$port"
  lab_exec cl -- "$netmc" run --server "$srv:$port" --quiet --json "$tmp/dds$tag.json" "${study[@]}" \
    >"$tmp/dds$tag.txt" 2>&1 || { cat "$tmp/dds$tag.txt"; return 1; }
  if cmp -s "$tmp/dds$tag.json" "$tmp/sim.json"; then
    echo "separate hosts ($tag): identical JSON to netmc sim"
  else
    echo "separate hosts ($tag) differ from netmc sim:"; diff "$tmp/sim.json" "$tmp/dds$tag.json" | head -20
    return 1
  fi
  for p in "x$tag" "y$tag" "server$tag"; do lab_stop "$p"; done
}

run_study multicast
if command -v fast-discovery-server >/dev/null; then
  for h in srv ax ay; do ip -n "$(lab_ns "$h")" route del 224.0.0.0/4 dev eth0; done
  lab_start discovery ds -- fast-discovery-server -i 0 -l "$(lab_addr ds)" -p 11811
  lab_wait_log discovery "Server is running" 10
  run_study discovery-server --discovery-server "$(lab_addr ds):11811"
  # The 2.9 tool ends on SIGINT (it ignores SIGTERM); lab's cleanup would SIGKILL it after 5 s.
  kill -INT "$(lab_pid discovery)" 2>/dev/null || true
else
  echo "fast-discovery-server (package fastdds-tools) not installed: discovery-server part skipped"
fi
