# Shared by the multi-process tests: a scratch directory, background processes stopped on exit,
# and the management port netmc-server reports once it listens. Source it after `set -e`.

tmp=$(mktemp -d)
pids=()
extra_cleanup=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  for step in "${extra_cleanup[@]}"; do eval "$step" || true; done
  rm -rf "$tmp"
}
trap cleanup EXIT

# A DDS domain of its own for each run, so concurrent runs do not meet.
domain=$(( 100 + RANDOM % 100 ))

# start NAME COMMAND...: runs COMMAND in the background, output in $tmp/NAME.log.
start() {
  local name=$1
  shift
  "$@" >"$tmp/$name.log" 2>&1 &
  pids+=($!)
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
