# shellcheck shell=bash
# Private test "hosts" made of Linux network namespaces, UDP loss with nftables, processes with a
# CLOCK_MONOTONIC of their own (time namespaces), and a check that nothing is left in them.
# Source it AFTER lib.sh (it needs $tmp and lib.sh's `cleanup`), from the test's main shell (not a
# subshell: it keeps state in shell variables). Safe under `set -euo pipefail`; needs bash >= 4.4.
#
#   lab_init                  root + iproute2 + namespaces, or "skipped: ..." and exit 77. Picks a
#                             tag (nmlab-PID-RANDOM, prefix of every namespace of this run) and a
#                             subnet 10.X.Y.0/24 (in $lab_net as "10.X.Y"); creates the bridge
#                             namespace $lab_tag-bridge (bridge br0, multicast snooping off).
#   lab_need_nft              nft usable in a namespace (nf_tables, numgen), else exit 77.
#   lab_need_timens           time namespaces can be made (unshare --time), else exit 77.
#   lab_host NAME [ADDRESS]   namespace $lab_tag-NAME: lo up, eth0 (veth to br0 in the bridge
#                             namespace) with the next address (.1, .2, ...)/24, or ADDRESS/24
#                             (e.g. a documentation address 192.0.2.10, so a test runs what the
#                             docs print; every host of a lab then takes one in one /24), and
#                             the route 224.0.0.0/4 dev eth0 (DDS discovery); net.ipv4.ipfrag_time 3 s.
#                             Nothing appears in the machine's own namespace: the lab addresses
#                             are reachable only from lab hosts, never from or to the outside.
#   lab_addr NAME             prints the host's address (10.X.Y.N, or its ADDRESS).
#   lab_ns NAME               prints the host's namespace name (for ip netns exec / ip -n).
#   lab_loss NAME PERCENT [out|in|both]
#                             random loss of PERCENT % (integer 0-100) of the UDP datagrams (IPv4
#                             and IPv6) on NAME's wire: out (default) = datagrams NAME sends,
#                             in = datagrams sent to NAME, both = each way independently. Applied
#                             in the bridge namespace (nftables bridge family, forward hook), so
#                             senders never notice (no sendto error) and each receiver of a
#                             multicast datagram draws on its own. TCP, ARP, and traffic inside a
#                             host (lo, its own multicast loopback) are never touched. A fragmented
#                             IPv4 datagram is lost as a whole with PERCENT % (only its first
#                             fragment is drawn). Calling it again replaces NAME's rules; PERCENT 0
#                             removes them. Needs lab_need_nft.
#   lab_loss_dropped NAME     prints how many datagrams NAME's lab_loss rules dropped so far (nft
#                             counters; 0 without rules; reset by every lab_loss call).
#   lab_partition A B on|off  a network partition between hosts A and B: every frame (IP, ARP,
#                             multicast copies) from A's wire to B's and back is dropped on the
#                             bridge while on; traffic of either with other hosts is untouched.
#                             Needs lab_need_nft.
#   lab_partition_dropped A B prints how many frames that partition dropped (0 without one).
#   Processes, in a host or on this machine's network (host "-"): processes.sh, which lib.sh
#   sources (lab_start, lab_pid, lab_pids, lab_kill, lab_wait, lab_wait_log, lab_stop,
#   lab_status, lab_fail, lab_keep_logs, lab_exec).
#   lab_cleanup               (runs automatically on exit, before lib.sh's cleanup; may also be
#                             called by the test) stops every lab_start process, kills whatever is
#                             still in the lab's namespaces (ip netns pids), verifies that no
#                             process of those sessions/namespaces is left, deletes the namespaces
#                             and verifies again (by namespace inode). Returns 1 and prints the
#                             offenders if anything remained; on exit that makes the test fail.
#   assert_loopback_only PATTERN
#                             for processes on the machine's own network namespace: every UDP
#                             socket and every TCP socket (listening or connected) of a process
#                             whose name (ss -p, i.e. /proc/PID/comm, at most 15 characters)
#                             matches the extended regex PATTERN must be bound to 127.0.0.0/8,
#                             ::1 or ::ffff:127.x. Wildcards (0.0.0.0, *, [::]), other addresses
#                             and multicast groups (224.0.0.0/4, ff00::/8: they receive on all
#                             interfaces) are printed and make it return 1, as does finding no
#                             socket of such a process at all.
#
# Processes must end on SIGTERM within $LAB_STOP_GRACE seconds: the cleanup SIGKILLs the others and
# the test fails (lab_stop of one process only says so). A process that leaves its session (setsid,
# daemon) is still found by the cleanup through its network namespace when it lives in a lab host.
# Tests must not replace the EXIT trap after sourcing this file.

if ! declare -F cleanup >/dev/null || ! declare -F lab_start >/dev/null || [ -z "${tmp:-}" ]; then
  echo "lab.sh: source lib.sh before lab.sh" >&2
  exit 1
fi

lab_tag=""
lab_net=""
lab__bridge=""
lab__next_addr=1
lab__namespaces=()      # every namespace of this run, bridge first
declare -A lab__hostidx=() lab__hostaddr=()

lab__skip() { echo "skipped: $*"; exit 77; }

lab_init() {
  [ -z "$lab_tag" ] || return 0
  [ "$(id -u)" -eq 0 ] || lab__skip "network namespaces need root"
  command -v ip >/dev/null || lab__skip "iproute2 (ip) is not installed"
  local tag=nmlab-$$-$RANDOM err
  if ! err=$(ip netns add "$tag-bridge" 2>&1); then
    lab__skip "creating network namespaces is not permitted here ($err)"
  fi
  lab_tag=$tag
  lab_net=10.$((100 + RANDOM % 100)).$((RANDOM % 250))
  lab__bridge=$tag-bridge
  lab__register_ns "$lab__bridge"
  if ! err=$(ip -n "$lab__bridge" link add br0 type bridge mcast_snooping 0 2>&1); then
    lab__skip "cannot create a bridge device ($err)"
  fi
  ip -n "$lab__bridge" link set br0 up
  local ns stale=()
  for ns in $(ip netns list | awk '{print $1}'); do
    if [[ $ns =~ ^nmlab-([0-9]+)-[0-9]+-bridge$ ]] && ! kill -0 "${BASH_REMATCH[1]}" 2>/dev/null; then
      stale+=("${ns%-bridge}-*")
    fi
  done
  if [ "${#stale[@]}" -gt 0 ]; then
    echo "lab: warning: namespaces of lab runs that died without cleanup: ${stale[*]}" \
      "(ip netns pids / ip netns del them)" >&2
  fi
}

lab__register_ns() {
  lab__namespaces+=("$1")
  local ino
  ino=$(stat -Lc %i "/run/netns/$1")
  lab__inode[$ino]=$1
}

lab_need_nft() {
  lab_init
  command -v nft >/dev/null || lab__skip "nft is not installed (package nftables)"
  local err
  if ! err=$(ip netns exec "$lab__bridge" nft -f - 2>&1 <<'EOF'
table bridge lab_probe {
  chain drop_udp { type filter hook forward priority 0; policy accept;
    iifname "v1" ip protocol udp ip frag-off & 0x1fff == 0 numgen random mod 100 < 1 counter drop
    oifname "v1" ip6 nexthdr udp numgen random mod 100 < 1 counter drop
  }
}
delete table bridge lab_probe
EOF
  ); then
    lab__skip "nftables does not work in a network namespace here ($err)"
  fi
}

lab_need_timens() {
  command -v unshare >/dev/null || lab__skip "unshare (util-linux) is not installed"
  local err
  if ! err=$(unshare --time --fork --monotonic 1 true 2>&1); then
    lab__skip "time namespaces cannot be made here ($err)"
  fi
}

lab_host() {
  local name=${1:?lab_host NAME [ADDRESS]} address=${2:-}
  [[ $name =~ ^[A-Za-z0-9_]+$ && $name != bridge ]] || { lab__err "lab_host: bad host name '$name'"; return 1; }
  [ -n "$lab_tag" ] || { lab__err "lab_host: call lab_init first"; return 1; }
  [ -z "${lab__hostidx[$name]+x}" ] || { lab__err "lab_host: host $name exists"; return 1; }
  [ "$lab__next_addr" -le 250 ] || { lab__err "lab_host: too many hosts"; return 1; }
  local ns=$lab_tag-$name idx=$lab__next_addr
  if [ -n "$address" ]; then
    [[ $address =~ ^[0-9]+\.[0-9]+\.[0-9]+\.[0-9]+$ ]] || { lab__err "lab_host: bad address '$address'"; return 1; }
  else
    address=$lab_net.$idx
  fi
  ip netns add "$ns" || return 1
  lab__register_ns "$ns"
  lab__hostidx[$name]=$idx
  lab__hostaddr[$name]=$address
  lab__next_addr=$((idx + 1))
  ip -n "$ns" link set lo up &&
  ip -n "$ns" link add eth0 type veth peer name "v$idx" netns "$lab__bridge" &&
  ip -n "$lab__bridge" link set "v$idx" master br0 up &&
  ip -n "$ns" addr add "$address/24" dev eth0 &&
  ip -n "$ns" link set eth0 up &&
  ip -n "$ns" route add 224.0.0.0/4 dev eth0 &&
  # Fragments orphaned by lab_loss (first fragment dropped) leave the reassembly queue after 3 s,
  # not 30, so heavy loss of large datagrams does not fill it (ipfrag_high_thresh).
  ip netns exec "$ns" sysctl -qw net.ipv4.ipfrag_time=3
}

lab__idx() {
  [ -n "${lab__hostidx[${1:-}]+x}" ] || { lab__err "lab: no host '${1:-}'"; return 1; }
  echo "${lab__hostidx[$1]}"
}
lab_addr() { lab__idx "${1:-}" >/dev/null && echo "${lab__hostaddr[$1]}"; }
lab_ns() { lab__idx "${1:-}" >/dev/null && echo "$lab_tag-$1"; }

lab_loss() {
  local name=${1:-} pct=${2:-} dir=${3:-out} idx
  idx=$(lab__idx "$name") || return 1
  [[ $pct =~ ^[0-9]+$ ]] && [ "$pct" -le 100 ] || { lab__err "lab_loss: PERCENT must be 0-100, not '$pct'"; return 1; }
  # On the wire: in the bridge namespace, on frames entering the bridge from NAME's veth (out) or
  # leaving it towards NAME (in). Dropping in the sender's own output path instead would make its
  # sendto() fail with EPERM, which real loss never does. IPv4: only unfragmented datagrams and
  # first fragments are drawn, so a fragmented datagram is lost with PERCENT % as a whole.
  local match="numgen random mod 100 < $pct " ports=() port rules=""
  [ "$pct" -lt 100 ] || match=""
  case $dir in
    out) ports=("iifname \"v$idx\"") ;;
    in) ports=("oifname \"v$idx\"") ;;
    both) ports=("iifname \"v$idx\"" "oifname \"v$idx\"") ;;
    *) lab__err "lab_loss: direction must be out, in or both, not '$dir'"; return 1 ;;
  esac
  for port in "${ports[@]}"; do
    rules+="    $port ip protocol udp ip frag-off & 0x1fff == 0 ${match}counter drop
    $port ip6 nexthdr udp ${match}counter drop
"
  done
  # Declaring the table first makes the delete valid whether or not it existed; one transaction.
  local table="bridge netmc_loss_$name"
  local script="table $table
delete table $table
"
  [ "$pct" -eq 0 ] || script+="table $table {
  chain drop_udp { type filter hook forward priority 0; policy accept;
$rules  }
}
"
  ip netns exec "$lab__bridge" nft -f - <<<"$script"
}

lab_loss_dropped() {
  local out n total=0
  lab__idx "${1:-}" >/dev/null || return 1
  out=$(ip netns exec "$lab__bridge" nft list table bridge "netmc_loss_$1" 2>/dev/null) || { echo 0; return 0; }
  for n in $(grep -o 'packets [0-9]*' <<<"$out" | awk '{print $2}'); do total=$((total + n)); done
  echo "$total"
}

lab_partition() {
  local a=${1:-} b=${2:-} state=${3:-} ia ib
  ia=$(lab__idx "$a") && ib=$(lab__idx "$b") || return 1
  local table="bridge netmc_partition_${a}_$b" script
  script="table $table
delete table $table
"
  case $state in
    on) script+="table $table {
  chain drop_all { type filter hook forward priority -10; policy accept;
    iifname \"v$ia\" oifname \"v$ib\" counter drop
    iifname \"v$ib\" oifname \"v$ia\" counter drop
  }
}
" ;;
    off) ;;
    *) lab__err "lab_partition: on or off, not '$state'"; return 1 ;;
  esac
  ip netns exec "$lab__bridge" nft -f - <<<"$script"
}

lab_partition_dropped() {
  local out n total=0
  lab__idx "${1:-}" >/dev/null && lab__idx "${2:-}" >/dev/null || return 1
  out=$(ip netns exec "$lab__bridge" nft list table bridge "netmc_partition_$1_$2" 2>/dev/null) || { echo 0; return 0; }
  for n in $(grep -o 'packets [0-9]*' <<<"$out" | awk '{print $2}'); do total=$((total + n)); done
  echo "$total"
}

lab_cleanup() {
  local - rc=0 ns i p left
  set +e
  lab__stop_sessions || rc=1
  for ns in "${lab__namespaces[@]}"; do
    p=$(ip netns pids "$ns" 2>/dev/null)
    [ -n "$p" ] || continue
    echo "lab cleanup: processes still in namespace $ns (not started by lab_start, or escaped" \
      "their session): $(tr '\n' ' ' <<<"$p")" >&2
    # shellcheck disable=SC2086 # $p: one pid a line
    kill -TERM $p 2>/dev/null
    for ((i = 0; i < 40; i++)); do
      p=$(ip netns pids "$ns" 2>/dev/null); [ -n "$p" ] || break; sleep 0.05
    done
    # shellcheck disable=SC2086
    [ -z "$p" ] || kill -KILL $p 2>/dev/null
  done
  for ((i = 0; i < 40; i++)); do left=$(lab__leftovers); [ -n "$left" ] || break; sleep 0.05; done
  if [ -n "$left" ]; then
    echo "lab cleanup: FAILED, processes left behind:" >&2
    ps -o pid,ppid,sid,stat,args -p "$(tr '\n' ',' <<<"$left" | sed 's/,*$//')" >&2
    rc=1
  fi
  for ((i = ${#lab__namespaces[@]} - 1; i >= 0; i--)); do
    ns=${lab__namespaces[i]}
    if ! ip netns del "$ns" 2>/dev/null && [ -e "/run/netns/$ns" ]; then
      echo "lab cleanup: FAILED to delete namespace $ns" >&2
      rc=1
    fi
  done
  lab__namespaces=()
  left=$(lab__leftovers)
  if [ -n "$left" ]; then
    echo "lab cleanup: FAILED, processes remain in deleted lab namespaces or sessions:" >&2
    ps -o pid,ppid,sid,stat,args -p "$(tr '\n' ',' <<<"$left" | sed 's/,*$//')" >&2
    rc=1
  fi
  return "$rc"
}

lab__on_exit() {
  local rc=$?
  set +e
  if ! lab_cleanup; then
    echo "lab: the cleanup check failed, so the test fails" >&2
    if [ "$rc" -eq 0 ] || [ "$rc" -eq 77 ]; then rc=1; fi
  fi
  cleanup   # lib.sh's
  exit "$rc"
}
trap lab__on_exit EXIT
# So that the EXIT trap (and so the cleanup) also runs when the test is interrupted or terminated.
trap 'exit 129' HUP
trap 'exit 130' INT
trap 'exit 143' TERM

# assert_loopback_only PATTERN: see the header.
assert_loopback_only() {
  local pattern=${1:?assert_loopback_only PATTERN} proto line laddr procs rest
  local names addr why whole name pid checked=0 bad=0
  for proto in udp tcp; do
    while IFS= read -r line; do
      read -r _ _ _ laddr _ procs <<<"$line"   # state recv-q send-q local peer process
      names=""
      rest=$procs
      while [[ $rest =~ \(\"([^\"]*)\",pid=([0-9]+) ]]; do
        whole=${BASH_REMATCH[0]} name=${BASH_REMATCH[1]} pid=${BASH_REMATCH[2]}
        if [[ $name =~ $pattern ]]; then names+=" $name(pid $pid)"; fi
        rest=${rest#*"$whole"}
      done
      [ -n "$names" ] || continue
      checked=$((checked + 1))
      addr=${laddr%:*}       # strip :port
      addr=${addr#[}
      addr=${addr%]}
      addr=${addr%%\%*}      # strip %interface
      case $addr in
        127.*|::1|::ffff:127.*) continue ;;
        0.0.0.0|'*'|::) why="wildcard bind (all interfaces)" ;;
        22[4-9].*|23[0-9].*|[fF][fF]*) why="multicast group bind (receives on all interfaces)" ;;
        *) why="non-loopback address" ;;
      esac
      [ "$bad" -gt 0 ] || echo "assert_loopback_only: sockets of /$pattern/ not on loopback:" >&2
      bad=$((bad + 1))
      echo "  $proto $laddr: $why:$names" >&2
      echo "    $line" >&2
    done < <(ss -H -n -p "--$proto" -a)
  done
  if [ "$checked" -eq 0 ]; then
    echo "assert_loopback_only: no UDP/TCP socket of a process named /$pattern/ (not running, or" \
      "a wrong pattern: ss shows /proc/PID/comm, at most 15 characters)" >&2
    return 1
  fi
  [ "$bad" -eq 0 ] || return 1
  echo "loopback only: $checked sockets of /$pattern/"
}
