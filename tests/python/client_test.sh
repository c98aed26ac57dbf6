#!/usr/bin/env bash
# netmc.Client against a running netmc-server (admin token) and two lockstep axis nodes on
# loopback: a submitted job's result equals netmc sim's, status and jobs list it, a long job is
# cancelled with the job's own token, another user's cancel without a token and a wrong admin
# token are refused with the server's message, a server that is not there raises naming it.
# Usage: client_test.sh BUILD_DIR
source "$(dirname "$0")/../integration/lib.sh" "$@"
export PYTHONPATH=$build/python

head -c 32 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/admin.token"
echo "not-the-token-0123456789abcdef0123456789" >"$tmp/wrong.token"
start x "$netmc_axis" --node it-x --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node it-y --axes y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --admin-token-file "$tmp/admin.token"
port=$(server_port 127.0.0.1)
"$netmc" sim --controller adrc --iterations 2 --json "$tmp/sim.json" -q >/dev/null

/usr/bin/python3 - "127.0.0.1:$port" "$tmp" <<'PY'
import json, sys
import netmc

server, tmp = sys.argv[1], sys.argv[2]
def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print("ok:", message, flush=True)

client = netmc.Client(server)
[job] = client.submit(controller="adrc", iterations=2)
study = client.watch(job)
check(study.to_json() == open(f"{tmp}/sim.json").read(),
      f"job {job} submitted from Python: its result equals netmc sim --json byte for byte")
check(study.table["e_max_m"].iloc[0] == json.loads(study.to_json())["runs"][0]["iterations"][-1]["e_max_m"],
      "and its table holds its numbers")
status = client.status(job)
check(status["jobs"][0]["state"] == "done", f"status of job {job}: {status['jobs'][0]['state']}")
check(any(int(entry["jobId"] if "jobId" in entry else entry.get("job_id", 0)) == job for entry in client.jobs()["jobs"]),
      "netmc jobs lists it")

# A long job, cancelled with its own token (kept by submit as netmc submit keeps it).
[long_job] = client.submit(controller="adrc+ilccc", iterations=500)
client.cancel(long_job)
try:
    client.watch(long_job)
    raise AssertionError("a cancelled job's watch returned")
except netmc.ServerError as error:
    check("cancel" in str(error), f"the cancelled job's watch raises ServerError: {str(error)[:90]}")

# Another client without the job's token (a fresh state dir) and with a wrong admin token.
import os
os.environ["XDG_STATE_HOME"] = f"{tmp}/other-user"
[other_job] = netmc.Client(server, token=f"{tmp}/admin.token").submit(controller="adrc", iterations=500)
os.environ["XDG_STATE_HOME"] = f"{tmp}/third-user"
for client_without, what in ((netmc.Client(server), "no token"),
                             (netmc.Client(server, token=f"{tmp}/wrong.token"), "a wrong admin token")):
    try:
        client_without.cancel(other_job)
        raise AssertionError(f"cancel with {what} was taken")
    except netmc.ServerError as error:
        check("token" in str(error), f"cancel with {what} refused: {str(error)[:100]}")
netmc.Client(server, token=f"{tmp}/admin.token").cancel(other_job)
check(netmc.Client(server).status(other_job)["jobs"][0]["state"] in ("cancelled", "failed"),
      "the admin token cancels any job")

for bad, error_type, text in ((dict(controller="no-such"), ValueError, "controller"),
                              (dict(iterations=0), ValueError, "--iterations")):
    try:
        client.submit(**bad)
        raise AssertionError(f"{bad} was submitted")
    except error_type as error:
        check(text in str(error), f"submit({bad}) raises {error_type.__name__}: {str(error)[:80]}")
try:
    netmc.Client("127.0.0.1:1").status()
    raise AssertionError("a server that is not there answered")
except netmc.ServerError as error:
    check("127.0.0.1:1" in str(error), f"no server there: {str(error)[:110]}")
PY
