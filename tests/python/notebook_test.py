"""examples/notebooks/delay-study.ipynb run top to bottom under nbclient (Debian's
python3-nbclient and python3-ipykernel), in a scratch copy of its folder, and its numbers checked
against the command line: the default study's JSON equals `netmc sim --iterations 10 --json`,
the Dask sweep's e_max column equals `netmc sweep --csv` of the same grid; its figures are written.
Its local Dask cluster's processes are checked gone afterwards.

Run: PYTHONPATH=BUILD/python python3 notebook_test.py SOURCE_DIR BUILD_DIR
"""
import csv
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile

import nbclient
import nbformat

source_dir, build = sys.argv[1], sys.argv[2]
netmc_cli = os.path.join(build, "client", "netmc")


def cli(*arguments):
    return subprocess.run([netmc_cli, *arguments], check=True, capture_output=True, text=True).stdout


def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print("ok:", message, flush=True)


def children():
    out = subprocess.run(["pgrep", "-P", str(os.getpid())], capture_output=True, text=True).stdout
    return {int(pid) for pid in out.split()}


# The kernel's debugger would warn about frozen modules on every start.
os.environ["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"
scratch = tempfile.mkdtemp(prefix="netmc-notebook-")
try:
    notebook_path = os.path.join(source_dir, "examples", "notebooks", "delay-study.ipynb")
    notebook = nbformat.read(notebook_path, as_version=4)
    check(all(not cell.get("outputs") for cell in notebook.cells if cell.cell_type == "code"),
          "the notebook is kept without outputs")
    before = children()
    client = nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": scratch}})
    client.execute()
    check(True, f"{len(notebook.cells)} cells ran top to bottom under nbclient")

    with open(os.path.join(scratch, "delay-study-summary.json")) as file:
        got = json.load(file)
    check(got["study_json"] == cli("sim", "--iterations", "10", "--json", "-", "-q"),
          "the notebook's default study equals netmc sim --iterations 10 --json byte for byte")
    sweep_csv = cli("sweep", "--delay-max", "1ms:10ms:10", "--seeds", "1..3", "--iterations", "5", "--csv", "-", "-q")
    rows = list(csv.DictReader(io.StringIO(sweep_csv)))
    check(got["sweep_rows"] == len(rows) and got["sweep_configurations"] == 4 * 10 * 3,
          f"the notebook's Dask sweep has the CLI's {len(rows)} rows of 120 configurations")
    check(got["sweep_e_max_m"] == [float(row["e_max_m"]) for row in rows], "and the CLI's e_max in every row")
    first_unstable = {}
    for row in rows:
        if row["diverged"] == "1":
            bound = float(row["delay_max_s"])
            first_unstable[row["run"]] = min(first_unstable.get(row["run"], bound), bound)
    check(got["first_unstable_s"] == first_unstable, f"the first unstable bounds it shows: {first_unstable}")
    for figure in ("delay-study-contour.png", "delay-study-learning.png", "delay-study-sweep.png"):
        path = os.path.join(scratch, figure)
        check(os.path.getsize(path) > 10000, f"{figure} written ({os.path.getsize(path)} bytes)")
    left = children() - before
    check(not left, f"no process of the notebook's kernel or Dask cluster left ({sorted(left)})")
finally:
    shutil.rmtree(scratch, ignore_errors=True)
