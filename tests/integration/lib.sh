# The one harness of the multi-process tests. Every script starts with
#   source "$(dirname "$0")/lib.sh" "$@"
# which sets the shell options and the failure trap, reads the build directory (the first
# argument, as netmc_add_script_test passes it) and names the programs: $netmc, $netmc_server,
# $netmc_axis; $source_dir is the repository, $here this folder. Then: a scratch directory $tmp,
# background processes started, waited for and stopped one way (processes.sh: start NAME
# COMMAND... here, lab_start in a namespaced host of lab.sh), and the management port
# netmc-server reports once it listens.
set -euo pipefail
trap 'echo "$0: failed at line $LINENO (exit $?)"' ERR
[ $# -ge 1 ] && [ -d "$1" ] || { echo "usage: $0 BUILD_DIR [arguments...]" >&2; exit 2; }
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
netmc=$build/client/netmc
netmc_server=$build/server/service/netmc-server
netmc_axis=$build/server/axis/netmc-axis

tmp=$(mktemp -d)
pids=()          # what start started, and any other background pid a test adds
extra_cleanup=()
source "$(dirname "${BASH_SOURCE[0]}")/processes.sh"
# stop_all: stops every process started so far: their sessions (lab__stop_sessions: SIGTERM, up
# to 5 s to go, then SIGKILL), then any other pid in pids the same way. Returns 1 if one had to be
# killed, or survives; their names may then be started again.
stop_all() {
  local rc=0 left="" pid
  lab__stop_sessions || rc=1
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for _ in $(seq 50); do
    left=""
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && left+=" $pid"; done
    [ -n "$left" ] || break
    sleep 0.1
  done
  if [ -n "$left" ]; then
    echo "cleanup: still running 5 s after SIGTERM, killed:$left" >&2
    # shellcheck disable=SC2086
    kill -KILL $left 2>/dev/null || true
    rc=1
  fi
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  pids=()
  return "$rc"
}
# On exit: stop_all; a process that had to be killed, or survives, fails the test (exit 1) even if
# its checks passed.
cleanup() {
  local rc=0
  stop_all || rc=1
  wait 2>/dev/null || true
  for step in "${extra_cleanup[@]}"; do eval "$step" || true; done
  rm -rf "$tmp"
  return "$rc"
}
trap 'status=$?; cleanup || status=1; exit "$status"' EXIT

# A block of 8 DDS domains of its own for each run ($domain up to $domain + 7: a test that starts
# another cluster beside or after the first takes the next ones), held by a lock while the test
# and anything it started live (the descriptor is inherited), so that tests running side by side
# never meet. 27 blocks, domains 16..231 (Fast DDS's ports allow up to 232).
netmc__domains=${TMPDIR:-/tmp}/netmc-test-domains
mkdir -p "$netmc__domains"
domain=""
for block in $(shuf -i 0-26); do
  exec {netmc__domain_fd}>"$netmc__domains/block-$block"
  if flock -n "$netmc__domain_fd"; then
    domain=$((16 + 8 * block))
    break
  fi
  exec {netmc__domain_fd}>&-
done
[ -n "$domain" ] || { echo "$0: all 27 blocks of DDS domains are taken by other tests" >&2; exit 1; }

# start NAME COMMAND...: lab_start NAME - -- COMMAND... (processes.sh: on this machine's network,
# in a session of its own, output in $tmp/NAME.log); its pid is appended to pids.
start() {
  local name=$1
  shift
  lab_start "$name" - -- "$@"
  pids+=("$(lab_pid "$name")")
}

# server_port HOST: waits up to 10 s for netmc-server (log $tmp/server.log) to listen.
server_port() {
  local port=""
  for _ in $(seq 100); do
    port=$(sed -n "s/.*listening on $1:\([0-9]*\).*/\1/p" "$tmp/server.log")
    if [ -n "$port" ]; then echo "$port"; return 0; fi
    sleep 0.1
  done
  echo "netmc-server did not start:" >&2
  cat "$tmp/server.log" >&2
  return 1
}

# same_json EXPECTED ACTUAL WHAT: passes (and says so) when the two JSON files are identical,
# else shows the first differences and fails.
same_json() {
  if cmp -s "$1" "$2"; then
    echo "$3 equals netmc sim: identical JSON ($(wc -c <"$1") bytes)"
  else
    echo "$3 differs from netmc sim:"
    diff "$1" "$2" | head -40
    return 1
  fi
}

# iteration_fields FILE FIELD...: one line per iteration of a result file (`netmc run --json`,
# one field a line): the FIELDs' values in that order (0 when absent); diverged_at_s is -1 for an
# iteration that did not diverge.
iteration_fields() {
  local file=$1
  shift
  awk -F': ' -v wanted="$*" '
    BEGIN { count = split(wanted, field, " ") }
    { v = $2; gsub(/,/, "", v) }
    /^ *"iteration":/ { if (n) print line(); n++; delete f }
    /^ *"[a-z0-9_]+":/ { k = $1; gsub(/[" ]/, "", k); f[k] = v }
    function line(   i, out, x) {
      out = ""
      for (i = 1; i <= count; i++) {
        x = field[i] == "diverged_at_s" ? (f["diverged"] == "true" ? f["diverged_at_s"] + 0 : -1) : f[field[i]] + 0
        out = out (i > 1 ? " " : "") x
      }
      return out
    }
    END { if (n) print line() }' "$file"
}
