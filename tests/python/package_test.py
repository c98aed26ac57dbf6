"""The Python package netmc against the command line it wraps: netmc.sim() gives `netmc sim
--json` byte for byte, its table one row per run, its traces numpy arrays of every cycle; sweeps
equal `netmc sweep --csv`; bad input raises the CLI's message; runs release the GIL; help() and
the stubs list every flag the CLI registers.

Run: PYTHONPATH=BUILD/python python3 package_test.py BUILD
"""
import csv as csv_module
import io
import json
import os
import subprocess
import sys
import threading
import unittest

import numpy

import netmc

BUILD = sys.argv.pop(1) if len(sys.argv) > 1 else "build"
NETMC = os.path.join(BUILD, "client", "netmc")


def cli(*arguments):
    return subprocess.run([NETMC, *arguments], check=True, capture_output=True, text=True).stdout


class SimTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.study = netmc.sim(iterations=5)
        cls.adrc_spec = json.loads(cli("sim", "--controller", "adrc", "--print-spec", "-q"))

    def test_json_equals_the_cli_byte_for_byte(self):
        self.assertEqual(self.study.to_json(), cli("sim", "--iterations", "5", "--json", "-", "-q"))

    def test_table_has_one_row_per_run_with_the_last_iterations_metrics(self):
        table = self.study.table
        runs = json.loads(self.study.to_json())["runs"]
        self.assertEqual(list(table["label"]), ["adrc", "adrc+pidccc", "adrc+ilccc", "adrc+ilccc+q20hz"])
        self.assertEqual(list(table["iteration"]), [5, 5, 5, 5])
        for row, run in zip(table.itertuples(), runs):
            self.assertEqual(row.e_max_m, run["iterations"][-1]["e_max_m"])
            self.assertEqual(row.tracking_rms_y_m, run["iterations"][-1]["tracking_rms_m"][1])
        self.assertEqual(len(self.study.iterations), 4 * 5)

    def test_trace_is_every_cycle_of_the_iteration_as_numpy_arrays(self):
        trace = self.study.trace("adrc+ilccc", 3)
        self.assertIsInstance(trace["x_m"], numpy.ndarray)
        self.assertEqual(len(trace["time_s"]), 1601)  # 8 s at 5 ms, both ends
        self.assertTrue(all(len(values) == 1601 for values in trace.values()))
        # The trace holds the iteration's own numbers: its largest |contour error| is its e_max.
        runs = json.loads(self.study.to_json())["runs"]
        e_max = runs[2]["iterations"][2]["e_max_m"]
        self.assertAlmostEqual(float(numpy.max(numpy.abs(trace["contour_error_m"][1:]))), e_max, delta=e_max * 1e-9)
        # Iterations differ (ILC learns), and the default is the last.
        self.assertFalse(numpy.array_equal(trace["y_m"], self.study.trace("adrc+ilccc", 1)["y_m"]))
        self.assertTrue(numpy.array_equal(self.study.trace("adrc+ilccc")["y_m"], self.study.trace("adrc+ilccc", 5)["y_m"]))
        # On demand (the default) the run is run again up to the iteration: the same trace, bit for
        # bit, as the one recorded while the study ran (traces="all").
        recorded = netmc.sim(iterations=5, traces="all")
        self.assertEqual(recorded.to_json(), self.study.to_json())
        for label, iteration in (("adrc+ilccc", 3), ("adrc", 5), ("adrc+pidccc", 1)):
            on_demand, kept = self.study.trace(label, iteration), recorded.trace(label, iteration)
            self.assertEqual(sorted(on_demand), sorted(kept))
            for name in kept:
                self.assertTrue(numpy.array_equal(on_demand[name], kept[name]), (label, iteration, name))
        with self.assertRaisesRegex(LookupError, "no traces"):
            netmc.sim(iterations=1, traces="none").trace("adrc")
        with self.assertRaisesRegex(ValueError, "traces: expected 'on-demand', 'all' or 'none'"):
            netmc.sim(iterations=1, traces="some")
        with self.assertRaisesRegex(IndexError, "iterations 1 to 5, got 6"):
            self.study.trace("adrc", 6)
        with self.assertRaisesRegex(KeyError, "no run 'pid'"):
            self.study.trace("pid")

    def test_keywords_are_the_cli_flags(self):
        study = netmc.sim(controller=["adrc", "adrc+ilccc"], delay="constant:20ms", compensate="predictor",
                          iterations=2, duration="1s")
        self.assertEqual(study.to_json(), cli("sim", "--controller", "adrc,adrc+ilccc", "--delay", "constant:20ms",
                                              "--compensate", "predictor", "--iterations", "2", "--duration", "1s",
                                              "--json", "-", "-q"))
        # spec= a dict is the JSON --spec reads.
        self.assertEqual(netmc.sim(spec=self.adrc_spec, iterations=1).labels, ["adrc"])

    def test_bad_input_raises_the_cli_message_and_the_interpreter_lives_on(self):
        cases = [
            (dict(delay="bogus"), ValueError, "--delay: unknown delay 'bogus'"),
            (dict(iterations="x"), ValueError, "--iterations"),
            (dict(iterations=0), ValueError, "--iterations"),
            (dict(iterations=float("nan")), ValueError, "iterations: expected a finite number"),
            (dict(controller={"a": 1}), TypeError, "controller: expected a string"),
            (dict(colour="red"), TypeError, "unexpected keyword argument 'colour'"),
            (dict(json="out.json"), TypeError, "returns what --json writes"),
            (dict(curve="yes"), TypeError, "--curve is a switch"),
            (dict(compensate="packets:horizon=0"), ValueError, "--compensate: expected packets:horizon=N"),
            (dict(spec=dict(SimTest.adrc_spec, controller={"name": "no-such-law"})), ValueError,
             "spec: controller: unknown name 'no-such-law'"),
        ]
        for keywords, error, message in cases:
            with self.subTest(keywords=keywords):
                with self.assertRaisesRegex(error, message.replace("+", "\\+")):
                    netmc.sim(**keywords)
        self.assertEqual(netmc.sim(iterations=1, duration="0.1s").labels[0], "adrc")

    def test_a_run_releases_the_gil(self):
        # A Python thread counts while the study runs: with the GIL held it could not.
        counted, done = [0], threading.Event()

        def count():
            while not done.is_set():
                counted[0] += 1

        counter = threading.Thread(target=count)
        counter.start()
        try:
            netmc.sim(iterations=20, threads=1)
        finally:
            done.set()
            counter.join()
        self.assertGreater(counted[0], 1000)

    def test_help_and_stubs_list_every_flag(self):
        help_text = netmc.sim.__doc__
        stubs = open(os.path.join(os.path.dirname(netmc.__file__), "__init__.pyi")).read()
        for line in cli("sim", "--help").splitlines():
            line = line.strip()
            if not line.startswith("--") or line.startswith("--help"):
                continue
            name = line.split()[0].split(",")[0][2:]
            if name in ("json", "csv", "plot", "plot-format", "print-spec", "list-presets", "list-controllers",
                        "list-compensators", "plant-parameters", "fail-on-unstable"):
                continue
            keyword = name.replace("-", "_")
            self.assertIn(f"    {keyword}=", help_text)
            self.assertIn(f"    {keyword}: Optional[", stubs)


class SweepTest(unittest.TestCase):
    def test_sweep_equals_the_cli_csv(self):
        csv = netmc.sweep_csv(delay_max="1ms:8ms:4", seeds="1..3", iterations=3)
        self.assertEqual(csv, cli("sweep", "--delay-max", "1ms:8ms:4", "--seeds", "1..3", "--iterations", "3",
                                  "--csv", "-", "-q"))
        table = netmc.sweep(delay_max="1ms:8ms:4", seeds="1..3", iterations=3)
        self.assertEqual(len(table), csv.count("\n") - 1)  # a row per configuration and iteration run
        self.assertEqual(list(table["config"].unique()), list(range(1, 49)))
        first = next(csv_module.DictReader(io.StringIO(csv)))
        self.assertEqual(table["e_max_m"].iloc[0], float(first["e_max_m"]))

    def test_repeatable_flags_repeat(self):
        csv = netmc.sweep_csv(controller="adrc", delay=["constant:1ms", "constant:5ms"], iterations=1, duration="0.2s")
        self.assertEqual(csv, cli("sweep", "--controller", "adrc", "--delay", "constant:1ms", "--delay",
                                  "constant:5ms", "--iterations", "1", "--duration", "0.2s", "--csv", "-", "-q"))

    def test_bad_grid(self):
        with self.assertRaisesRegex(ValueError, "--seeds"):
            netmc.sweep(seeds="5..1")
        with self.assertRaisesRegex(TypeError, "unexpected keyword argument 'shard'"):
            netmc.sweep(shard="1/2")
        with self.assertRaisesRegex(ValueError, "tasks: expected an integer"):
            netmc.sweep(controller="adrc", iterations=1, client=object(), tasks=0)


if __name__ == "__main__":
    unittest.main(verbosity=2)
