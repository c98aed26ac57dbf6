#!/usr/bin/env bash
# A process given --discovery-server says so when no server answers (DiscoveryServerWatch), and
# stays quiet when one does; a server on loopback is reached even with --interface eth0 (loopback
# is added, and the log says so). In a namespaced host, so its loopback and eth0 are the test's own.
# Usage: discovery_server_warning.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
source "$(dirname "$0")/lab.sh"
lab_init
lab_host h
dds=(--domain "$domain" --transport udp)
warning='no Fast DDS discovery server answered at 127.0.0.1:11811 within 5 s'

# No server at 127.0.0.1:11811: the warning comes within the bound (5 s, plus start-up).
lab_start lonely h -- "$netmc_axis" --node lonely --axes x "${dds[@]}" --discovery-server 127.0.0.1:11811
lab_wait_log lonely 'serving' 10
start_ms=$(lab__now_ms)
lab_wait_log lonely "$warning" 8 || lab_fail "no warning within 8 s of serving"
echo "without a server, $(( $(lab__now_ms) - start_ms )) ms after 'serving':"
grep -o 'warning.*' "$tmp/lonely.log"
lab_stop lonely

# A server runs: no warning, however long the process waits.
lab_start fds h -- fast-discovery-server -i 0 -l 127.0.0.1 -p 11811
lab_wait_log fds 'Server is running' 10
lab_start axis h -- "$netmc_axis" --node ds-x --axes x "${dds[@]}" --interface eth0 --discovery-server 127.0.0.1:11811
lab_start server h -- "$netmc_server" --listen 127.0.0.1:7300 "${dds[@]}" --interface eth0 \
  --discovery-server 127.0.0.1:11811
lab_wait_log server 'listening on' 10
lab_wait_log axis 'serving' 10
# --interface eth0 without loopback: 127.0.0.1 added for the server on loopback, and said.
grep -q '127.0.0.1 added to the interfaces DDS may use' "$tmp/axis.log" || lab_fail "loopback not added"
grep -o 'warning.*' "$tmp/axis.log"
sleep 7
for log in axis server; do
  if grep -q 'no Fast DDS discovery server answered' "$tmp/$log.log"; then lab_fail "$log warned with a server running"; fi
done
echo "with a server running: no warning after 7 s"
lab_exec h -- "$netmc" nodes --server 127.0.0.1:7300 | tee "$tmp/nodes.txt"
grep -q 'ds-x' "$tmp/nodes.txt" || lab_fail "the node is not listed through the discovery server on loopback"
for log in server axis fds; do lab_stop "$log"; done
echo "discovery server warning: PASS"
