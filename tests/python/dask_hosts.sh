#!/usr/bin/env bash
# The Dask recipe of docs/user-guide/clusters.md on two hosts (network namespaces of lab.sh, one
# /24 of their own): a scheduler on host "scheduler", two single-thread workers on host
# "workers" that reach it by its address, and netmc.sweep(client=...) from the scheduler's host:
# the CSV equals netmc sweep's of the same grid byte for byte. Nothing is left running.
# Usage: dask_hosts.sh BUILD_DIR
source "$(dirname "$0")/../integration/lib.sh" "$@"
source "$(dirname "$0")/../integration/lab.sh"
lab_init
lab_host scheduler
lab_host workers
export PYTHONPATH=$build/python
S=$(lab_addr scheduler)
W=$(lab_addr workers)
port=8786

lab_start dask-scheduler scheduler -- dask-scheduler --host "$S" --port "$port" --no-dashboard --no-show
lab_wait_log dask-scheduler "Scheduler at" 60
for n in 1 2; do
  lab_start "dask-worker-$n" workers -- dask-worker "tcp://$S:$port" --nthreads 1 --no-nanny --host "$W" \
    --no-dashboard --name "worker-$n" --local-directory "$tmp/worker-$n"
done
"$netmc" sweep --delay-max 1ms:8ms:4 --seeds 1..3 --iterations 3 -q --csv "$tmp/cli.csv" >/dev/null
lab_exec scheduler -- /usr/bin/python3 - "tcp://$S:$port" "$tmp/dask.csv" <<'PY'
import sys
from distributed import Client
import netmc
client = Client(sys.argv[1], timeout=60)
client.wait_for_workers(2, timeout=60)
workers = sorted(info["host"] for info in client.scheduler_info()["workers"].values())
print("workers at", workers)
with open(sys.argv[2], "w") as out:
    out.write(netmc.sweep_csv(delay_max="1ms:8ms:4", seeds="1..3", iterations=3, client=client))
client.close()
PY
cmp "$tmp/cli.csv" "$tmp/dask.csv" ||
  { echo "FAIL: the sweep on the two hosts differs from netmc sweep's"; diff "$tmp/cli.csv" "$tmp/dask.csv" | head; exit 1; }
echo "Dask on two hosts: scheduler $S, two workers $W: $(($(wc -l <"$tmp/cli.csv") - 1)) rows equal to netmc sweep --csv"
