#!/usr/bin/env bash
# The lab console in a real headless browser (Debian's chromium and chromium-driver, driven by
# python3-selenium: console_test.py), on loopback, with two realtime axis nodes:
#   1. plain HTTP, then 2. HTTPS (the management endpoint's certificate): the page lists both
#      nodes; a job started from the page without the token is refused and with it runs, its
#      live contour growing while it runs; a second job is cancelled from the page, refused
#      without the token; the page's table of the first job's iterations equals what
#      `netmc watch --json` (as `netmc run --json` writes it) reports; no browser console error;
#   3. a 5 kHz realtime job (h = 0.2 ms) run from the command line alternately without a browser
#      and with the console open and plotting it live, three times each: the deadline misses are
#      reported, and the best run with the browser may have at most twice the misses of the worst
#      run without it plus 1 % of a run's cycles (the runs' own spread, and Chromium's own work on
#      the loop's cores); the server's thread that serves the console runs on the normal
#      scheduler, its CPU time reported
#      (Chromium shares these 2 cores with the loop: the loop's processes run SCHED_FIFO with
#      --cpu-latency 0, as docs/benchmarks.md's 5 kHz figures; Chromium at nice 10).
# Usage: console_browser.sh BUILD_DIR
source "$(dirname "$0")/../integration/lib.sh" "$@"
python=/usr/bin/python3  # Debian's, with python3-selenium

head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/token"
export NETMC_TOKEN_FILE=$tmp/token
bash "$here/../../scripts/make-lab-pki.sh" "$tmp/pki" --server console-server --management 127.0.0.1 >/dev/null

# Nodes and server; generous limits and watchdog: the browser beside the loop on 2 cores delays
# some cycles by tens of ms (once 54 ms: a 50 ms watchdog quick-stopped an axis), and an axis that
# trips would fail the job (a diverging one only stops its iteration). The watchdog itself is
# integration.chaos_partition's subject, not this test's.
start_lab() {  # [--realtime-scheduling] [netmc-server flags...]
  local scheduling=()
  if [[ ${1:-} == --realtime-scheduling ]]; then
    scheduling=(--rt-priority 80 --cpu-latency 0)
    shift
  fi
  local extra=("$@")
  for axis in x y; do
    start "$axis-$RANDOM" "$netmc_axis" --node con-$axis --axes $axis --clock realtime \
      --command-limit 10 --position-window -1:1 --velocity-limit 10 --watchdog 500 --domain "$domain" --transport udp \
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
# The thread that serves the browser and management clients, and the one that checks submitted
# specs, run on the normal scheduler, so that their work never holds a CPU against the loop's
# SCHED_FIFO threads; every other thread of the server keeps SCHED_FIFO.
server_pid=$(for p in $(lab_pids server); do [[ $(ps -o comm= -p "$p") == netmc-server ]] && echo "$p"; done)
threads=$(ps -L -o tid=,cls=,comm= -p "$server_pid")
echo "server threads (tid, scheduler, name): $(echo $threads)"
misplaced=$(awk -v main="$server_pid" '{serving = $1 == main || $3 == "validate"}
  serving && $2 != "TS" || !serving && $2 != "FF"' <<<"$threads")
[[ -z $misplaced && $(grep -c ' validate$' <<<"$threads") == 1 ]] ||
  { echo "FAIL: expected the serving and validating threads on the normal scheduler, the others SCHED_FIFO"; exit 1; }
fast=(--quiet --clock realtime --controller adrc --sample-period 0.2ms --duration 4s --iterations 1)
# Alternately without and with the browser, three times each: the runs' own spread is part of the
# answer. Also reported: the CPU time the server's serving thread (console and management) took
# during each run, the console's own cost to the server.
serving_ticks() { awk '{print $14 + $15}' "/proc/$server_pid/task/$server_pid/stat"; }
# One run first, not counted: the first job of a freshly started lab makes its DDS readers and
# touches its memory (its misses here were 874, 1489 and 3781 against 119-460 for later runs).
"$netmc" run --server "127.0.0.1:$port" "${fast[@]}" --json "$tmp/fast-warm-up.json" >/dev/null
rounds=3
for round in $(seq $rounds); do
  before=$(serving_ticks)
  "$netmc" run --server "127.0.0.1:$port" "${fast[@]}" --json "$tmp/fast-alone-$round.json" >/dev/null
  echo $(( $(serving_ticks) - before )) >"$tmp/serving-alone-$round"
  rm -f "$tmp/watching" "$tmp/stop-watching" "$tmp/points-$round"
  nice -n 10 "$python" "$here/console_watch.py" --url "$url" --seconds 60 --ready "$tmp/watching" \
    --stop "$tmp/stop-watching" --points "$tmp/points-$round" >"$tmp/watch-browser-$round.log" 2>&1 &
  watcher=$!
  for _ in $(seq 300); do [ -f "$tmp/watching" ] && break; sleep 0.1; done
  [ -f "$tmp/watching" ] || { echo "FAIL: the browser did not open the console"; cat "$tmp/watch-browser-$round.log"; exit 1; }
  before=$(serving_ticks)
  "$netmc" run --server "127.0.0.1:$port" "${fast[@]}" --json "$tmp/fast-browser-$round.json" >/dev/null
  echo $(( $(serving_ticks) - before )) >"$tmp/serving-browser-$round"
  touch "$tmp/stop-watching"
  wait "$watcher" || { echo "FAIL: the browser watching the job reported:"; cat "$tmp/watch-browser-$round.log"; exit 1; }
done
"$python" - "$tmp" "$rounds" "$(getconf CLK_TCK)" <<'PY'
import json, sys
tmp, rounds, tick_s = sys.argv[1], range(1, int(sys.argv[2]) + 1), 1 / int(sys.argv[3])
def first(path):
    return json.load(open(path))["runs"][0]["iterations"][0]
def serving_ms(kind):
    return [int(open(f"{tmp}/serving-{kind}-{r}").read()) * tick_s * 1e3 for r in rounds]
alone = [first(f"{tmp}/fast-alone-{r}.json") for r in rounds]
browsed = [first(f"{tmp}/fast-browser-{r}.json") for r in rounds]
points = [int(open(f"{tmp}/points-{r}").read()) for r in rounds]
run_cycles = 20000
cycles = len(alone) * run_cycles
def listed(values, form="{}"):
    return ", ".join(form.format(v) for v in values)
a = sum(m["deadline_misses"] for m in alone)
b = sum(m["deadline_misses"] for m in browsed)
print(f"5 kHz, {len(alone)} x 4 s each ({run_cycles} cycles a run), alternately: deadline misses without a browser "
      f"{listed(m['deadline_misses'] for m in alone)}; with the console open and plotting "
      f"{listed(m['deadline_misses'] for m in browsed)} (points drawn {listed(points)}); "
      f"rate {a / cycles * 100:.2f} % vs {b / cycles * 100:.2f} %; tau p99 "
      f"{listed((m['tau_p99_s'] * 1e3 for m in alone), '{:.3f}')} vs "
      f"{listed((m['tau_p99_s'] * 1e3 for m in browsed), '{:.3f}')} ms; the server's serving thread's CPU time "
      f"during a run {listed(serving_ms('alone'), '{:.0f}')} vs {listed(serving_ms('browser'), '{:.0f}')} ms")
assert min(points) > 0, "the browser plotted nothing of the job"
# The browser's cost to the loop, within the runs' own spread. Chromium here runs on the loop's
# own 2 cores (in a lab it runs on the operator's computer): after a warm-up and with the browser
# settled, its own work still added misses, 140-231 without against 319-673 with it in one run
# here, while the server's serving thread took only 10-20 ms more CPU a run (likely cause: this
# kernel is PREEMPT_NONE, so a SCHED_FIFO thread woken on a CPU waits out a system call there).
# So the best run with the browser may have at most twice the misses of the worst run without,
# plus 1 % of a run's cycles; a console that made the loop wait (a lock, a full queue) misses most
# cycles of a run.
worst_alone = max(m["deadline_misses"] for m in alone)
best_browsed = min(m["deadline_misses"] for m in browsed)
assert best_browsed <= 2 * worst_alone + 0.01 * run_cycles, "the browser cost the loop deadlines"
PY
stop_lab
