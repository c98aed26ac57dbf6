"""netmc.sweep(client=...) on a Dask cluster of separate processes (a scheduler and two
single-thread workers, on loopback): the result equals `netmc sweep --csv` of the same grid byte
for byte, and a worker killed mid-sweep costs only the re-runs of its tasks: the sweep completes
with every configuration exactly once. Every process started is stopped and checked gone.

Run: PYTHONPATH=BUILD/python python3 dask_sweep_test.py BUILD
"""
import os
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time

import distributed

import netmc

BUILD = sys.argv[1]
NETMC = os.path.join(BUILD, "client", "netmc")


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def cli_csv(*arguments):
    return subprocess.run([NETMC, "sweep", *arguments, "--csv", "-", "-q"], check=True, capture_output=True,
                          text=True).stdout


def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print("ok:", message, flush=True)


def main():
    scratch = tempfile.mkdtemp(prefix="netmc-dask-")
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    processes = []

    def start(*command):
        log = open(os.path.join(scratch, f"{len(processes)}.log"), "w")
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        processes.append(process)
        return process

    try:
        start("dask-scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard", "--no-show")
        workers = [start("dask-worker", address, "--nthreads", "1", "--no-nanny", "--host", "127.0.0.1",
                         "--no-dashboard", "--name", f"worker-{n}", "--local-directory", os.path.join(scratch, f"w{n}"))
                   for n in (1, 2)]
        client = distributed.Client(address, timeout=60)
        client.wait_for_workers(2, timeout=60)
        check(len(client.scheduler_info()["workers"]) == 2, "a scheduler and two worker processes are up")

        # The grid: 48 configurations, as Dask tasks, equal to one process's sweep.
        grid = dict(delay_max="1ms:8ms:4", seeds="1..3", iterations=3)
        distributed_csv = netmc.sweep_csv(client=client, **grid)
        check(distributed_csv == cli_csv("--delay-max", "1ms:8ms:4", "--seeds", "1..3", "--iterations", "3"),
              "48 configurations on two workers equal netmc sweep --csv byte for byte")
        table = netmc.sweep(client=client, tasks=5, **grid)
        check(list(table["config"].unique()) == list(range(1, 49)), "5 tasks of interleaved parts: configurations 1..48")

        # A longer grid (40 configurations of 60 iterations); worker 2 is killed once results
        # come back, while it holds tasks.
        long_grid = dict(controller="adrc,adrc+ilccc", delay_max="1ms:8ms:4", seeds="1..5", iterations=60)
        outcome = {}

        def run():
            try:
                outcome["csv"] = netmc.sweep_csv(client=client, **long_grid)
            except BaseException as error:  # reported below
                outcome["error"] = error

        sweeper = threading.Thread(target=run)
        sweeper.start()
        victim = workers[1]
        held = 0
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and sweeper.is_alive():
            processing = client.processing()
            stored = sum(len(keys) for keys in client.has_what().values())
            held = max((len(keys) for worker, keys in processing.items() if "worker-2" in str(
                client.scheduler_info()["workers"].get(worker, {}).get("name", ""))), default=0)
            if stored >= 2 and held > 0:
                break
            time.sleep(0.02)
        check(sweeper.is_alive() and held > 0, f"worker 2 holds {held} task(s) while the sweep runs")
        os.kill(victim.pid, signal.SIGKILL)
        victim.wait(timeout=30)
        sweeper.join(timeout=300)
        check("error" not in outcome, f"the sweep completed after the kill ({outcome.get('error')!r})")
        check(len(client.scheduler_info()["workers"]) == 1, "one worker left")
        expected = cli_csv("--controller", "adrc,adrc+ilccc", "--delay-max", "1ms:8ms:4", "--seeds", "1..5",
                           "--iterations", "60")
        check(outcome["csv"] == expected,
              "with a worker killed mid-sweep: equal to netmc sweep --csv, every configuration exactly once")
        client.close()
    finally:
        for process in processes:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGTERM)
        for process in processes:
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
        left = [p.pid for p in processes if p.poll() is None]
        subprocess.run(["rm", "-rf", scratch])
    check(not left, "no scheduler or worker process left")


if __name__ == "__main__":
    main()
