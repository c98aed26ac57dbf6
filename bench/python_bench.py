"""The Python package's speed against the CLI's, and a Dask sweep's scaling (docs/benchmarks.md).

  PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py build [--repeats 7]

1. netmc.sim() of the default study (4 runs x 20 iterations, all cores) against `netmc sim`'s own
   process, alternately, the median of each (the CLI's time includes its process start).
2. netmc.sweep(client=...) of one grid on a scheduler with one single-thread worker process,
   then with two: configurations per second of each, and their ratio.
"""
import argparse
import os
import socket
import statistics
import subprocess
import sys
import time

import distributed

import netmc

parser = argparse.ArgumentParser()
parser.add_argument("build")
parser.add_argument("--repeats", type=int, default=7)
arguments = parser.parse_args()
cli = os.path.join(arguments.build, "client", "netmc")

python_s, cli_s = [], []
for _ in range(arguments.repeats):
    started = time.perf_counter()
    netmc.sim()
    python_s.append(time.perf_counter() - started)
    started = time.perf_counter()
    subprocess.run([cli, "sim", "-q"], check=True, stdout=subprocess.DEVNULL)
    cli_s.append(time.perf_counter() - started)
print(f"default study: netmc.sim() {statistics.median(python_s) * 1e3:.1f} ms, netmc sim {statistics.median(cli_s) * 1e3:.1f} ms "
      f"(medians of {arguments.repeats}; ratio {statistics.median(python_s) / statistics.median(cli_s):.3f})")


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


grid = dict(delay_max="1ms:8ms:8", seeds="1..5", iterations=20)  # 160 configurations
rates = {}
for workers in (1, 2):
    port = free_port()
    processes = [subprocess.Popen(["dask-scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard",
                                   "--no-show"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    processes += [subprocess.Popen(["dask-worker", f"tcp://127.0.0.1:{port}", "--nthreads", "1", "--no-nanny",
                                    "--host", "127.0.0.1", "--no-dashboard"],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) for _ in range(workers)]
    try:
        client = distributed.Client(f"tcp://127.0.0.1:{port}", timeout=60)
        client.wait_for_workers(workers, timeout=60)
        netmc.sweep(client=client, controller="adrc", iterations=1, duration="0.1s")  # workers import netmc
        timings = []
        for _ in range(3):
            started = time.perf_counter()
            table = netmc.sweep(client=client, **grid)
            timings.append(time.perf_counter() - started)
        configurations = table["config"].nunique()
        rates[workers] = configurations / min(timings)
        print(f"Dask sweep, {workers} single-thread worker(s): {configurations} configurations in "
              f"{min(timings):.2f} s (best of 3), {rates[workers]:.1f} configurations/s")
        client.close()
    finally:
        for process in processes:
            process.terminate()
        for process in processes:
            process.wait(timeout=30)
print(f"two workers / one worker: {rates[2] / rates[1]:.2f}x")
sys.exit(0)
