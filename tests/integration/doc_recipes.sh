#!/usr/bin/env bash
# The docs' recipes run as written: the commands are taken from the Markdown itself
# (doc_recipes.py pulls the blocks marked `<!-- recipe NAME host=HOST ... -->`), each block on its
# host, a network namespace whose address is the one the docs print (192.0.2.10 the server's PC,
# 192.0.2.21 the axes' controller; documentation addresses, private to this lab). The blocks run
# from a directory where `build` and `scripts` lead to this checkout, as a reader who built from
# source types them. Background blocks keep running until the recipe ends; the others run in the
# foreground with a timeout and must succeed. Then the recipe's own checks.
#   two-hosts         docs/operations/distributed-runs.md: axes on one host, server and client on
#                     another, multicast discovery: the job completes.
#   discovery-server  the same page: the same through fast-discovery-server, with no multicast
#                     route on either host: the job completes.
#   dds-security      docs/operations/security.md: the same two hosts; the job completes through
#                     authenticated, encrypted DDS; a server without a certificate on the server
#                     host's network (eth0) finds no axis.
#   management-tls    docs/operations/hostile-networks-and-clients.md: `netmc nodes` over TLS with
#                     the token; a client without the CA is refused.
#   commissioning     docs/operations/commissioning.md: one emulated Modbus axis enabled, moved
#                     +10 mm and back (read back within 1 um), jogged and quick-stopped; the same
#                     without the admin token, and a move outside the window, are refused by name.
# Usage: doc_recipes.sh BUILD_DIR RECIPE
source "$(dirname "$0")/lib.sh" "$@"
recipe=${2:?usage: doc_recipes.sh BUILD_DIR RECIPE}
source "$(dirname "$0")/lab.sh"
lab_init

# The hosts the docs name, by the name their recipe markers use.
declare -A host_address=([server]=192.0.2.10 [axis]=192.0.2.21)

steps=$tmp/steps
/usr/bin/python3 "$here/doc_recipes.py" "$recipe" "$steps" "$source_dir"/docs/operations/*.md >"$tmp/manifest"
echo "recipe $recipe: $(wc -l <"$tmp/manifest") blocks"
for host in $(awk '{print $2}' "$tmp/manifest" | sort -u); do
  [ -n "${host_address[$host]+x}" ] || lab_fail "recipe $recipe: unknown host '$host'"
  lab_host "$host" "${host_address[$host]}"
done
if [ "$recipe" = discovery-server ]; then
  # No multicast at all: discovery can only go through the Discovery Server.
  for host in $(awk '{print $2}' "$tmp/manifest" | sort -u); do ip -n "$(lab_ns "$host")" route del 224.0.0.0/4; done
fi

reader=$tmp/reader
mkdir -p "$reader"
ln -s "$build" "$reader/build"
ln -s "$source_dir/scripts" "$reader/scripts"
cd "$reader"
# The recipes use the default domain; this run takes one of the tests' (shared memory is not
# namespaced), through the variable every netmc DDS process reads.
export NETMC_DOMAIN=$domain

started=()
while read -r n host mode ready; do
  echo "--- block $n on $host ($mode):"
  sed 's/^/    /' "$steps/$n.sh"
  if [ "$mode" = background ]; then
    line_no=0
    # One process per command line (a continued line ends in a backslash), as in its own terminal.
    while IFS= read -r line; do
      [[ $line =~ ^[[:space:]]*(#|$) ]] && continue
      line_no=$((line_no + 1))
      name=b$n-$line_no
      lab_start "$name" "$host" -- bash -c "$line"
      started+=("$name")
      if [ "$ready" != - ]; then
        lab_wait_log "$name" "$ready" 20 || lab_fail "block $n: '$line' did not print /$ready/"
      fi
    done < <(sed -e ':a' -e '/\\$/N; s/\\\n//; ta' "$steps/$n.sh")
  else
    status=0
    lab_exec "$host" -- timeout 120 bash -euo pipefail "$steps/$n.sh" >"$tmp/block$n.log" 2>&1 || status=$?
    sed 's/^/    | /' "$tmp/block$n.log"
    [ "$status" -eq 0 ] || lab_fail "block $n on $host exited with status $status"
  fi
done <"$tmp/manifest"

# The recipe's own checks, beyond every foreground block having succeeded.
last_log=$tmp/block$(tail -n 1 "$tmp/manifest" | awk '{print $1}').log
case $recipe in
  two-hosts | discovery-server | dds-security)
    grep -q 'job 1 done' "$tmp"/b*.log || lab_fail "no server log says 'job 1 done'"
    echo "the job completed: $(grep -h 'job 1 done' "$tmp"/b*.log)"
    grep -A1 '^run ' "$last_log" ;;
esac
case $recipe in
  discovery-server)
    if grep -l 'no Fast DDS discovery server answered' "$tmp"/b*.log; then
      lab_fail "a process warned that the discovery server did not answer"
    fi ;;
  dds-security)
    # A server without a certificate of the lab's CA sees none of the secure nodes.
    rogue_exit=0
    lab_start rogue server -- build/server/service/netmc-server --listen 127.0.0.1:7301 --interface eth0 \
      --transport udp --discovery-timeout 3000 --dds-name rogue-server
    lab_wait_log rogue 'listening on' 20
    lab_exec server -- build/client/netmc run --server 127.0.0.1:7301 --axes stage1.x,stage1.y \
      --iterations 1 >"$tmp/rogue_run.txt" 2>&1 || rogue_exit=$?
    [ "$rogue_exit" -ne 0 ] && grep -q 'no axis node for axis stage1.x was discovered' "$tmp/rogue_run.txt" ||
      { cat "$tmp/rogue_run.txt"; lab_fail "a server without a certificate reached the secure axes"; }
    echo "a server without a certificate: $(grep -o 'no axis node for axis stage1.x was discovered' "$tmp/rogue_run.txt" | head -1)" ;;
  management-tls)
    grep -q 'axes' "$last_log" || lab_fail "netmc nodes over TLS printed no node table"
    plain_exit=0
    lab_exec server -- env NETMC_TOKEN_FILE=token build/client/netmc nodes >"$tmp/plain.txt" 2>&1 || plain_exit=$?
    [ "$plain_exit" -ne 0 ] && grep -q 'speaks TLS only' "$tmp/plain.txt" ||
      { cat "$tmp/plain.txt"; lab_fail "a client without NETMC_TLS_CA was not told to set it"; }
    echo "a client without the CA: $(head -n 1 "$tmp/plain.txt")" ;;
  commissioning)
    for expected in 'axis x: holding, Operation enabled at 0.055000 m' \
        'axis x: holding, Operation enabled at 0.065000 m.*target 0.065000 m' \
        'axis x: holding, Operation enabled at 0.055000 m.*target 0.055000 m' \
        'axis x: off, \(Quick stop active\|Switch on disabled\)'; do
      grep -q "$expected" "$last_log" || lab_fail "the commissioning printed no line like '$expected'"
    done
    # The jog: 1 s at -5 mm/s, and the ramps (10 ms each way at 0.5 m/s^2): about 5 mm.
    jogged=$(sed -n '4p' <(grep '^axis x: ' "$last_log") | sed 's/.* at \([0-9.]*\) m,.*/\1/')
    awk -v p="$jogged" 'BEGIN { d = (0.055 - p) * 1e3; printf "jogged %.3f mm\n", d; exit (d > 4 && d < 7) ? 0 : 1 }' ||
      lab_fail "the jog did not move the axis about 5 mm: it ended at $jogged m"
    refused_exit=0
    lab_exec axis -- build/client/netmc enable bench x >"$tmp/no_token.txt" 2>&1 || refused_exit=$?
    [ "$refused_exit" -ne 0 ] && grep -q 'enable: needs the admin token' "$tmp/no_token.txt" ||
      { cat "$tmp/no_token.txt"; lab_fail "an enable without the admin token was not refused"; }
    echo "without the token: $(head -n 1 "$tmp/no_token.txt")"
    lab_exec axis -- env NETMC_TOKEN_FILE=admin.token build/client/netmc enable bench x >/dev/null
    refused_exit=0
    lab_exec axis -- env NETMC_TOKEN_FILE=admin.token build/client/netmc move bench x --to 200mm \
      >"$tmp/outside.txt" 2>&1 || refused_exit=$?
    [ "$refused_exit" -ne 0 ] && grep -q "refused: the target 0.2 m is outside the axis's window \[0, 0.12\] m" "$tmp/outside.txt" ||
      { cat "$tmp/outside.txt"; lab_fail "a move outside the window was not refused by name"; }
    echo "outside the window: $(head -n 1 "$tmp/outside.txt")"
    lab_exec axis -- env NETMC_TOKEN_FILE=admin.token build/client/netmc disable bench x ;;
esac
for name in "${started[@]}"; do lab_stop "$name"; done
echo "recipe $recipe runs as written"
