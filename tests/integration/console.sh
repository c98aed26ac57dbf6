#!/usr/bin/env bash
# netmc-server's console without a browser (docs/operations/console.md): a realtime job on two
# axis nodes started through POST /api/jobs with the token (refused without); /metrics during the
# job shows it running and both nodes up and passes promtool check metrics, and after it the
# counters moved; GET /api/jobs/ID gives the same iterations as netmc watch --json; then the
# hostile checks (console_hostile.py) with a job running.
# Usage: console.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"

printf 'console-token-%s\n' "$RANDOM$RANDOM$RANDOM" >"$tmp/token"
chmod 600 "$tmp/token"
for axis in x y; do
  # A generous command limit: a loaded machine (the browser test beside) delays cycles by tens of ms.
  start "$axis" "$netmc_axis" --node con-$axis --axes $axis --clock realtime --domain "$domain" \
    --command-limit 10 --position-window -1:1 --velocity-limit 10 \
    --transport udp
done
start server "$netmc_server" --listen 127.0.0.1:0 --http :0 --domain "$domain" --transport udp \
  --token-file "$tmp/token"
port=$(server_port 127.0.0.1)
http=$(sed -n 's|.*console on http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$tmp/server.log")
url=http://127.0.0.1:$http
token=$(cat "$tmp/token")
server_pid=${pids[-1]}

for _ in $(seq 100); do
  [[ $(curl -s "$url/api/state" | python3 -c 'import json,sys; print(len(json.load(sys.stdin)["nodes"]))') == 2 ]] && break
  sleep 0.1
done
job='{"preset":"seed001","controller":"adrc","iterations":3,"clock":"realtime"}'
code=$(curl -s -o "$tmp/refused.json" -w '%{http_code}' -X POST -d "$job" "$url/api/jobs")
[[ $code == 401 ]] || { echo "FAIL: a job without the token answered $code"; exit 1; }
curl -s -f -X POST -H "Authorization: Bearer $token" -d "$job" "$url/api/jobs" >"$tmp/accepted.json"
id=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["job"])' "$tmp/accepted.json")
echo "POST /api/jobs: refused without the token (401), job $id started with it"

# During the job.
for _ in $(seq 100); do
  curl -s "$url/metrics" >"$tmp/during.txt"
  grep -q '^netmc_jobs{state="running"} 1$' "$tmp/during.txt" && break
  sleep 0.1
done
grep -q '^netmc_jobs{state="running"} 1$' "$tmp/during.txt" || { echo "FAIL: /metrics does not show the job running"; cat "$tmp/during.txt"; exit 1; }
grep -q '^netmc_nodes_up 2$' "$tmp/during.txt" || { echo "FAIL: /metrics does not show both nodes up"; exit 1; }
promtool check metrics <"$tmp/during.txt"
echo "/metrics during the job: netmc_jobs{state=\"running\"} 1, netmc_nodes_up 2; promtool check metrics: no complaint"

NETMC_TOKEN_FILE=$tmp/token "$netmc" watch "$id" --server "127.0.0.1:$port" --json "$tmp/watch.json" >/dev/null
curl -s -f "$url/metrics" >"$tmp/after.txt"
promtool check metrics <"$tmp/after.txt"
curl -s -f "$url/api/jobs/$id" >"$tmp/job.json"
# The state every page gets (and a reload) counts the finished job's every iteration: 3 / 3.
for _ in $(seq 30); do
  curl -s -f "$url/api/state" >"$tmp/state.json"
  done_count=$(python3 -c 'import json,sys; j=[j for j in json.load(open(sys.argv[1]))["jobs"] if str(j["job_id"]) == sys.argv[2]][0]; print(j["state"], j.get("iterations_done", 0), j["iterations_total"])' "$tmp/state.json" "$id")
  [ "$done_count" = "done 3 3" ] && break
  sleep 0.2
done
[ "$done_count" = "done 3 3" ] || { echo "FAIL: /api/state shows the finished job as '$done_count', not 'done 3 3'"; exit 1; }
echo "/api/state after the job: done, 3 / 3 iterations"
python3 - "$tmp/watch.json" "$tmp/job.json" "$tmp/after.txt" <<'PY'
import json, sys
watched = json.load(open(sys.argv[1]))["runs"][0]["iterations"]
console = json.load(open(sys.argv[2]))
assert console["status"]["state"] == "done", console["status"]
shown = sorted(console["iterations"], key=lambda m: m["iteration"])
assert len(shown) == len(watched) == 3, (len(shown), len(watched))
for w, c in zip(watched, shown):
    for key in ("e_max_m", "e_rms_m", "e_sum_m", "deadline_misses", "tau_p99_s"):
        assert float(w[key]) == float(c[key]), (key, w[key], c[key])
metrics = dict(line.rsplit(" ", 1) for line in open(sys.argv[3]) if line and not line.startswith("#"))
assert float(metrics["netmc_iterations_total"]) == 3, metrics["netmc_iterations_total"]
assert float(metrics['netmc_jobs{state="done"}']) == 1
assert float(metrics["netmc_loop_delay_seconds_count"]) > 0
assert float(metrics['netmc_loop_delay_seconds{quantile="0.99"}']) > 0
print(f"GET /api/jobs/ID = netmc watch --json for 3 iterations (e_max {shown[-1]['e_max_m'] * 1e6:.2f} um); "
      f"after the job: netmc_iterations_total 3, netmc_jobs{{state=\"done\"}} 1, "
      f"loop delay count {metrics['netmc_loop_delay_seconds_count']}")
PY

# The hostile checks with a job running, so the live feed has something to send.
curl -s -f -X POST -H "Authorization: Bearer $token" -d "$job" "$url/api/jobs" >/dev/null
/usr/bin/python3 "$(dirname "$0")/console_hostile.py" "$http" "$server_pid" --slow-reader-seconds 8 \
  --token-file "$tmp/token"
grep -q 'job [0-9]* failed' "$tmp/server.log" && { echo "FAIL: a job failed during the hostile checks"; grep failed "$tmp/server.log"; exit 1; }
echo "no job failed"

# A server without --token-file: its console is read-only, and it checks Host and Origin all the same.
start open_server "$netmc_server" --listen 127.0.0.1:0 --http :0 --domain "$((domain + 1))" --transport udp
for _ in $(seq 100); do grep -q 'console on' "$tmp/open_server.log" && break; sleep 0.1; done
open_url=$(sed -n 's|.*console on \(http://127.0.0.1:[0-9]*\)/.*|\1|p' "$tmp/open_server.log")
grep -q 'read-only' "$tmp/open_server.log" || { echo "FAIL: the log does not say the console is read-only"; exit 1; }
code=$(curl -s -o "$tmp/read_only.json" -w '%{http_code}' -X POST -d "$job" "$open_url/api/jobs")
[[ $code == 403 ]] && grep -q 'read-only' "$tmp/read_only.json" ||
  { echo "FAIL: a job posted to a console without a token answered $code: $(cat "$tmp/read_only.json")"; exit 1; }
code=$(curl -s -o /dev/null -w '%{http_code}' -X POST -d '{}' "$open_url/api/jobs/1/cancel")
[[ $code == 403 ]] || { echo "FAIL: a cancel posted to a console without a token answered $code"; exit 1; }
code=$(curl -s -o /dev/null -w '%{http_code}' -H 'Host: evil.example' "$open_url/api/state")
[[ $code == 403 ]] || { echo "FAIL: a foreign Host got $code from a console without a token"; exit 1; }
code=$(curl -s -o /dev/null -w '%{http_code}' -H 'Origin: http://evil.example' -H 'Content-Type: text/plain' \
  -X POST -d "$job" "$open_url/api/jobs")
[[ $code == 403 ]] || { echo "FAIL: a cross-site POST got $code from a console without a token"; exit 1; }
[[ $(curl -s -o /dev/null -w '%{http_code}' "$open_url/api/state") == 200 ]] || { echo "FAIL: the read-only console does not read"; exit 1; }
echo "without --token-file: start and cancel 403 (read-only), a foreign Host 403, a cross-site POST 403; /api/state 200"

# /metrics: the build, the process, one series per CiA 402 state, and a node that left reads 0.
check_metrics() {  # FILE UP_X UP_Y
  promtool check metrics <"$1"
  python3 - "$@" <<'PY'
import sys
path, up_x, up_y = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
samples = {}
for line in open(path):
    if line.startswith("#") or not line.strip():
        continue
    name, value = line.rsplit(" ", 1)
    samples[name] = float(value)
assert any(k.startswith("netmc_build_info{version=") and v == 1 for k, v in samples.items()), "no netmc_build_info"
assert samples["process_resident_memory_bytes"] > 1e6, samples["process_resident_memory_bytes"]
assert samples["process_open_fds"] >= 3 and samples["process_start_time_seconds"] > 1.7e9
assert samples['netmc_node_up{node="con-x"}'] == up_x and samples['netmc_node_up{node="con-y"}'] == up_y
assert not any(k.startswith("netmc_axis_fault{") and "state=" in k for k in samples), "a state label on netmc_axis_fault"
for node, axis in [("con-x", "x"), ("con-y", "y")]:
    states = {k: v for k, v in samples.items() if k.startswith(f'netmc_axis_state{{node="{node}",axis="{axis}"')}
    if node == "con-x" and not up_x:
        assert not states, states  # a node that left has no drive listed
        continue
    assert len(states) == 8 and sum(states.values()) == 1, states
    # Trips and quick stops: a counter per listed axis (none happened here).
    assert samples[f'netmc_axis_trips_total{{node="{node}",axis="{axis}"}}'] == 0
    assert samples[f'netmc_axis_quick_stops_total{{node="{node}",axis="{axis}"}}'] == 0
# The jobs run above: each one's latest iteration and its e_max, as two gauges of the same series.
last_e_max = {k: v for k, v in samples.items() if k.startswith("netmc_job_last_e_max_meters{")}
last_iteration = {k: v for k, v in samples.items() if k.startswith("netmc_job_last_iteration{")}
assert last_e_max and all(0 < v < 0.05 for v in last_e_max.values()), last_e_max
assert {k.split("{", 1)[1] for k in last_e_max} == {k.split("{", 1)[1] for k in last_iteration}, (last_e_max, last_iteration)
assert all(v >= 1 for v in last_iteration.values()), last_iteration
assert "netmc_iterations_failed_total" in samples
for k, v in samples.items():
    if k.startswith("netmc_node_round_trip_seconds{"):
        assert 0 <= v < 1, (k, v)
print(f"  {path.rsplit('/', 1)[-1]}: netmc_build_info, process_* (RSS {samples['process_resident_memory_bytes'] / 2**20:.1f} MiB), "
      f"netmc_node_up con-x {up_x:g} con-y {up_y:g}, netmc_axis_state: 8 series an axis, one of them 1, "
      f"trips and quick stops 0, netmc_job_last_e_max_meters of {len(last_e_max)} job(s)")
PY
}
curl -s -f "$url/metrics" >"$tmp/metrics-both.txt"
check_metrics "$tmp/metrics-both.txt" 1 1
# The Grafana dashboard (docker/grafana-dashboard.json): every query is PromQL promtool reads (as
# recording rules), and every series it names is on this page.
python3 - "$source_dir/docker/grafana-dashboard.json" "$tmp/metrics-both.txt" "$tmp/dashboard-rules.yml" <<'PY'
import json, re, sys
dashboard = json.load(open(sys.argv[1]))
page = open(sys.argv[2]).read()
exprs = [target["expr"] for panel in dashboard["panels"] for target in panel["targets"]]
names = {name for expr in exprs for name in re.findall(r"\b(?:netmc|process)_[a-z_]+", expr)}
# A family is on the page by its TYPE line (a node whose clock is not measured yet has no sample).
missing = sorted(name for name in names if f"# TYPE {name} " not in page)
assert not missing, f"the dashboard names series /metrics does not have: {missing}"
with open(sys.argv[3], "w") as rules:
    rules.write("groups:\n- name: dashboard\n  rules:\n")
    for i, expr in enumerate(exprs):
        rules.write(f"  - record: dashboard_query_{i}\n    expr: {json.dumps(expr)}\n")
print(f"  the Grafana dashboard: {len(dashboard['panels'])} panels, {len(exprs)} queries over {len(names)} series, all on /metrics")
PY
promtool check rules "$tmp/dashboard-rules.yml" >/dev/null ||
  { echo "FAIL: promtool does not read the dashboard's queries"; promtool check rules "$tmp/dashboard-rules.yml"; exit 1; }
lab_stop x
for _ in $(seq 60); do
  curl -s -f "$url/metrics" >"$tmp/metrics-left.txt"
  grep -q '^netmc_node_up{node="con-x"} 0$' "$tmp/metrics-left.txt" && break
  sleep 0.2
done
check_metrics "$tmp/metrics-left.txt" 0 1
echo "/metrics: promtool clean with both nodes and after con-x left (its netmc_node_up reads 0)"
