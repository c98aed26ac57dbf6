#!/usr/bin/env bash
# The lab console in a real headless browser (Debian's chromium and chromium-driver, driven by
# python3-selenium: console_test.py), on loopback, with two realtime axis nodes:
#   1. plain HTTP, then 2. HTTPS (the management endpoint's certificate): the page lists both
#      nodes; a job started from the page without the token is refused and with it runs, its
#      live contour growing while it runs; a second job is cancelled from the page, refused
#      without the token; the page's table of the first job's iterations equals what
#      `netmc watch --json` (as `netmc run --json` writes it) reports; no browser console error;
#   3. a 5 kHz realtime job (h = 0.2 ms) run from the command line alternately without a browser
#      and with the console open and plotting it live, twice each: the deadline misses are
#      reported, and the better run with the browser may exceed the worse run without it by at
#      most a quarter plus 1 % of a run's cycles (the runs' own spread on this machine)
#      (Chromium shares these 2 cores with the loop: the loop's processes run SCHED_FIFO with
#      --cpu-latency 0, as docs/benchmarks.md's 5 kHz figures; Chromium at nice 10).
# Usage: console_browser.sh BUILD_DIR
source "$(dirname "$0")/../integration/lib.sh" "$@"
python=/usr/bin/python3  # Debian's, with python3-selenium

head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/token"
export NETMC_TOKEN_FILE=$tmp/token
bash "$here/../../scripts/make-lab-pki.sh" "$tmp/pki" --server console-server --management 127.0.0.1 >/dev/null

# Nodes and server; generous limits: the browser beside the loop on 2 cores delays some cycles by
# tens of ms, and an axis that trips would fail the job (a diverging one only stops its iteration).
start_lab() {  # [--realtime-scheduling] [netmc-server flags...]
  local scheduling=()
  if [[ ${1:-} == --realtime-scheduling ]]; then
    scheduling=(--rt-priority 80 --cpu-latency 0)
    shift
  fi
  local extra=("$@")
  for axis in x y; do
    start "$axis-$RANDOM" "$netmc_axis" --node con-$axis --axes $axis --clock realtime \
      --command-limit 10 --position-window -1:1 --velocity-limit 10 --domain "$domain" --transport udp \
      "${scheduling[@]}"
  done
  : >"$tmp/server.log"
  start server "$netmc_server" --listen 127.0.0.1:0 --http :0 --domain "$domain" \
    --transport udp --token-file "$tmp/token" "${scheduling[@]}" "${extra[@]}"
  port=$(server_port 127.0.0.1)
  url=$(sed -n 's|.*console on \(https*://127.0.0.1:[0-9]*/\).*|\1|p' "$tmp/server.log")
}
stop_lab() {
  stop_all
  domain=$(( domain + 1 ))
}

browse() {  # MODE [extra console_test.py flags]
  local mode=$1
  shift
  nice -n 10 "$python" "$here/console_test.py" --url "$url" --token "$(cat "$tmp/token")" --expect-nodes con-x,con-y \
    --results-json "$tmp/page-$mode.json" --preset seed001 --controller adrc --iterations 2 --clock realtime "$@"
  local id
  id=$("$python" -c 'import json,sys; print(json.load(open(sys.argv[1]))["job"])' "$tmp/page-$mode.json")
  "${tls_client[@]}" "$netmc" watch "$id" --server "127.0.0.1:$port" --quiet --json "$tmp/watch-$mode.json" >/dev/null
  "$python" - "$tmp/page-$mode.json" "$tmp/watch-$mode.json" "$mode" <<'PY'
import json, sys
page = json.load(open(sys.argv[1]))["iterations"]
watched = json.load(open(sys.argv[2]))["runs"][0]["iterations"]
assert len(page) == len(watched) == 2, (len(page), len(watched))
for p, w in zip(sorted(page, key=lambda m: m["iteration"]), watched):
    for key in ("e_max_m", "e_rms_m", "e_sum_m", "deadline_misses"):
        assert float(p[key]) == float(w[key]), (key, p[key], w[key])
print(f"{sys.argv[3]}: the page's table of {len(page)} iterations equals netmc watch --json "
      f"(e_max {page[-1]['e_max_m'] * 1e6:.2f} um)")
PY
}

tls_client=(env)
start_lab
browse http
stop_lab

tls_client=(env NETMC_TLS_CA="$tmp/pki/ca.pem")
start_lab --tls-cert "$tmp/pki/management.pem" --tls-key "$tmp/pki/management.key"
[[ $url == https://* ]] || { echo "FAIL: the console does not speak HTTPS with --tls-cert"; exit 1; }
browse https --insecure
stop_lab

# 3. The miss rate at 5 kHz, without and with the console open in the browser: the loop's
# processes as a 5 kHz loop is run here (SCHED_FIFO, CPUs kept out of deep idle; docs/benchmarks.md,
# "Realtime over DDS"), the browser at normal priority.
tls_client=(env)
start_lab --realtime-scheduling
fast=(--quiet --clock realtime --controller adrc --sample-period 0.2ms --duration 4s --iterations 1)
# Alternately without and with the browser, twice: the runs' own spread is part of the answer.
for round in 1 2; do
  "$netmc" run --server "127.0.0.1:$port" "${fast[@]}" --json "$tmp/fast-alone-$round.json" >/dev/null
  rm -f "$tmp/watching" "$tmp/stop-watching" "$tmp/points-$round"
  nice -n 10 "$python" "$here/console_watch.py" --url "$url" --seconds 60 --ready "$tmp/watching" \
    --stop "$tmp/stop-watching" --points "$tmp/points-$round" >"$tmp/watch-browser-$round.log" 2>&1 &
  watcher=$!
  for _ in $(seq 300); do [ -f "$tmp/watching" ] && break; sleep 0.1; done
  [ -f "$tmp/watching" ] || { echo "FAIL: the browser did not open the console"; cat "$tmp/watch-browser-$round.log"; exit 1; }
  "$netmc" run --server "127.0.0.1:$port" "${fast[@]}" --json "$tmp/fast-browser-$round.json" >/dev/null
  touch "$tmp/stop-watching"
  wait "$watcher" || { echo "FAIL: the browser watching the job reported:"; cat "$tmp/watch-browser-$round.log"; exit 1; }
done
"$python" - "$tmp" <<'PY'
import json, sys
tmp = sys.argv[1]
def first(path):
    return json.load(open(path))["runs"][0]["iterations"][0]
alone = [first(f"{tmp}/fast-alone-{r}.json") for r in (1, 2)]
browsed = [first(f"{tmp}/fast-browser-{r}.json") for r in (1, 2)]
points = [int(open(f"{tmp}/points-{r}").read()) for r in (1, 2)]
cycles = 2 * 20000
a = sum(m["deadline_misses"] for m in alone)
b = sum(m["deadline_misses"] for m in browsed)
print("5 kHz, 2 x 4 s each (20000 cycles a run), alternately: deadline misses without a browser "
      f"{alone[0]['deadline_misses']}, {alone[1]['deadline_misses']}; with the console open and plotting "
      f"{browsed[0]['deadline_misses']}, {browsed[1]['deadline_misses']} (points drawn {points[0]}, {points[1]}); "
      f"rate {a / cycles * 100:.2f} % vs {b / cycles * 100:.2f} %; tau p99 "
      f"{alone[0]['tau_p99_s'] * 1e3:.3f}/{alone[1]['tau_p99_s'] * 1e3:.3f} vs "
      f"{browsed[0]['tau_p99_s'] * 1e3:.3f}/{browsed[1]['tau_p99_s'] * 1e3:.3f} ms")
assert min(points) > 0, "the browser plotted nothing of the job"
# The same rate within the runs' own spread: a browser that costs the loop deadlines does so in
# every run with it, so the better run with the browser may exceed the worse run without by at
# most a quarter plus 1 % of a run's cycles. (One run's spike is this host's, not the browser's:
# once, 971 misses with the browser against 280 in the other run with it and 176/329 without.)
worst_alone = max(m["deadline_misses"] for m in alone)
best_browsed = min(m["deadline_misses"] for m in browsed)
assert best_browsed <= 1.25 * worst_alone + 0.01 * (cycles / 2), "the browser cost the loop deadlines"
PY
stop_lab
