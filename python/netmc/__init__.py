"""netmc from Python: the studies of `netmc sim` and `netmc sweep`, run in-process.

    import netmc
    study = netmc.sim(iterations=5, delay="constant:20ms", compensate="predictor")
    study.table                       # pandas DataFrame, one row per run (its last iteration)
    study.trace("adrc+ilccc", 5)      # that iteration's per-cycle signals as numpy arrays
    study.to_json()                   # exactly what `netmc sim --json` writes

    netmc.sweep(delay_max="1ms:8ms:4", seeds="1..3", iterations=3)             # all cores here
    netmc.sweep(delay_max="1ms:8ms:4", seeds="1..3", client=distributed_client)  # on a Dask cluster

Every keyword is a flag of the command line (`delay_max=` is `--delay-max`), parsed by the CLI's
own parser: help(netmc.sim) lists them. Bad input raises ValueError with the CLI's message; an
unknown keyword raises TypeError. Runs release the GIL.
"""

from __future__ import annotations

import io
import json as _json
import math
import numbers
import os
import shutil
import subprocess
import tempfile
import uuid
from typing import Any, Dict, List, Optional

from . import _core

__version__ = _core.version
__all__ = ["sim", "sweep", "sweep_csv", "Study", "Client", "ServerError", "set_log_level", "__version__"]

_FLAGS = {command: {flag["name"]: flag for flag in _core.command_flags(command)} for command in ("sim", "sweep")}

# Flags that write files or run elsewhere: the Python calls return their results instead.
_NOT_KEYWORDS = {
    "sim": {"json", "csv", "plot", "plot-format", "print-spec", "list-presets", "list-controllers",
            "list-compensators", "plant-parameters", "fail-on-unstable"},
    "sweep": {"csv", "json", "plot", "server", "shard"},
}


def set_log_level(level: str) -> None:
    """The level of netmc's log on standard error: trace, debug, info, warning (default), error, off."""
    _core.set_log_level("warn" if level == "warning" else level)


def _text(keyword: str, value: Any) -> str:
    if isinstance(value, bool):
        raise TypeError(f"{keyword}: expected a string or a number, got a bool")
    if isinstance(value, str):
        return value
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        number = float(value)
        if not math.isfinite(number):
            raise ValueError(f"{keyword}: expected a finite number, got {number}")
        return repr(number)
    raise TypeError(f"{keyword}: expected a string, a number or a list of them, got {type(value).__name__}")


def _arguments(command: str, keywords: Dict[str, Any]) -> List[str]:
    """Keyword flags as the command line's arguments, in the order given."""
    flags = _FLAGS[command]
    arguments: List[str] = []
    for keyword, value in keywords.items():
        name = keyword.replace("_", "-")
        flag = flags.get(name)
        if flag is None or name in _NOT_KEYWORDS[command]:
            reason = (f"netmc.{command}() returns what --{name} writes" if flag is not None
                      else f"netmc {command} has no flag --{name}")
            raise TypeError(f"{command}() got an unexpected keyword argument '{keyword}' ({reason}; "
                            f"help(netmc.{command}) lists the keywords)")
        if value is None or value is False:
            continue
        if not flag["takes_value"]:
            if value is not True:
                raise TypeError(f"{keyword}: expected True or False (--{name} is a switch), got {type(value).__name__}")
            arguments.append("--" + name)
            continue
        values = list(value) if isinstance(value, (list, tuple)) else [value]
        if not values:
            raise ValueError(f"{keyword}: expected at least one value")
        texts = [_text(keyword, item) for item in values]
        if flag["repeatable"]:
            for text in texts:
                arguments += ["--" + name, text]
        else:
            arguments += ["--" + name, ",".join(texts)]
    return arguments


def _with_spec(keywords: Dict[str, Any]):
    """spec= a dict: written to a private temporary file the CLI's --spec reads."""
    spec = keywords.get("spec")
    if not isinstance(spec, dict):
        return keywords, None
    handle = tempfile.NamedTemporaryFile("w", suffix=".json", prefix="netmc-spec-", delete=False)
    with handle:
        _json.dump(spec, handle)
    return dict(keywords, spec=handle.name), handle.name


def _keyword_doc(command: str) -> str:
    lines = []
    for name, flag in _FLAGS[command].items():
        if name in _NOT_KEYWORDS[command]:
            continue
        kind = "True" if not flag["takes_value"] else (flag["type_name"] or "VALUE")
        if flag["repeatable"] and flag["takes_value"]:
            kind += " or a list"
        lines.append(f"    {name.replace('-', '_')}={kind}\n        {flag['description']}")
    return "\n".join(lines)


class Study:
    """The result of netmc.sim(): what `netmc sim` prints and writes, as Python objects."""

    def __init__(self, raw: Dict[str, Any]):
        self._json: str = raw["json"]
        self.text: str = raw["table"]
        self._results: Optional[Dict[str, Any]] = None
        self._traces = raw.get("traces")  # _core.StudyTraces (numpy arrays made on demand), or None
        self._trace_cache: Dict[Any, Dict[str, Any]] = {}
        self.labels: List[str] = list(raw["labels"])

    @property
    def results(self) -> Dict[str, Any]:
        """The study's results, as `netmc sim --json` writes them, parsed."""
        if self._results is None:
            self._results = _json.loads(self._json)
        return self._results

    @classmethod
    def from_json(cls, text: str) -> "Study":
        """A Study of a results file's text (netmc sim, run or watch --json); it has no traces."""
        results = _json.loads(text)
        if not isinstance(results, dict) or not isinstance(results.get("runs"), list):
            raise ValueError("results: expected the JSON of netmc sim --json ({\"runs\": [...]})")
        study = cls({"json": text, "table": "", "labels": [run.get("label", "") for run in results["runs"]]})
        study._results = results
        return study

    def to_json(self) -> str:
        """Exactly what `netmc sim --json` writes for the same flags."""
        return self._json

    @property
    def table(self):
        """A pandas DataFrame, one row per run: the run's description and its last iteration's metrics."""
        import pandas

        return pandas.DataFrame([_row(run, run["iterations"][-1] if run["iterations"] else {})
                                 for run in self.results["runs"]])

    @property
    def iterations(self):
        """A pandas DataFrame, one row per run and iteration."""
        import pandas

        return pandas.DataFrame([_row(run, iteration) for run in self.results["runs"] for iteration in run["iterations"]])

    def trace(self, label: str, iteration: Optional[int] = None) -> Dict[str, Any]:
        """The per-cycle signals of run `label`'s iteration (1-based; default: its last) as numpy
        arrays, named as the columns of `netmc sim --csv` (time_s, x_ref_m, x_m, contour_error_m, ...)."""
        if label not in self.labels:
            raise KeyError(f"label: no run '{label}' in this study (runs: {', '.join(self.labels)})")
        if self._traces is None:
            raise LookupError(f"run '{label}': this study has no traces (netmc.sim(traces='none'), a server's job, "
                              "or a results file)")
        run = self.labels.index(label)
        count = self._traces.iterations(run)
        if iteration is None:
            iteration = count
        if isinstance(iteration, bool) or not isinstance(iteration, numbers.Integral):
            raise TypeError(f"iteration: expected an integer, got {type(iteration).__name__}")
        if not 1 <= iteration <= count:
            raise IndexError(f"iteration: run '{label}' has iterations 1 to {count}, got {iteration}")
        key = (run, int(iteration))
        if key not in self._trace_cache:
            self._trace_cache[key] = self._traces.columns(run, int(iteration) - 1)
        return dict(self._trace_cache[key])

    def __repr__(self) -> str:
        return self.text

    def _repr_html_(self) -> str:
        return self.table._repr_html_()


class ServerError(RuntimeError):
    """A netmc-server refused a request, failed a job, or could not be reached (the CLI's message)."""


def _program() -> str:
    """The netmc program beside this package: a build tree's, else the one on PATH (package netmc)."""
    here = os.path.dirname(os.path.abspath(__file__))
    built = os.path.join(here, "..", "..", "client", "netmc")
    if os.path.isfile(built) and os.access(built, os.X_OK):
        return os.path.normpath(built)
    found = shutil.which("netmc")
    if not found:
        raise ServerError("netmc: the program is not installed (apt-get install ./netmc_*.deb, or build it)")
    return found


class Client:
    """A running netmc-server, through the netmc program's own commands (submit, watch, status,
    cancel, jobs) and so with its security: `token` the admin token's file (what the CLI reads
    from NETMC_TOKEN_FILE), `tls` the CA's certificate file or a dict(ca=, cert=, key=) (the
    CLI's NETMC_TLS_CA, NETMC_TLS_CERT, NETMC_TLS_KEY). A job submitted here keeps its cancel
    token where `netmc submit` keeps it, so this user may cancel it without the admin token."""

    def __init__(self, server: str = "127.0.0.1:7300", *, token: Any = None, tls: Any = None,
                 timeout: Optional[float] = None):
        if not isinstance(server, str) or not server:
            raise TypeError("server: expected 'HOST:PORT'")
        self.server = server
        self.timeout = timeout
        self._environment = dict(os.environ)
        for name in ("NETMC_TOKEN_FILE", "NETMC_TLS_CA", "NETMC_TLS_CERT", "NETMC_TLS_KEY"):
            self._environment.pop(name, None)
        if token is not None:
            self._environment["NETMC_TOKEN_FILE"] = _text("token", token)
        if isinstance(tls, dict):
            unknown = set(tls) - {"ca", "cert", "key"}
            if unknown or "ca" not in tls:
                raise TypeError(f"tls: expected dict(ca=FILE[, cert=FILE, key=FILE]), got keys {sorted(tls)}")
            for key, name in (("ca", "NETMC_TLS_CA"), ("cert", "NETMC_TLS_CERT"), ("key", "NETMC_TLS_KEY")):
                if key in tls:
                    self._environment[name] = _text(f"tls {key}", tls[key])
        elif tls is not None:
            self._environment["NETMC_TLS_CA"] = _text("tls", tls)

    def _run(self, *arguments: str) -> str:
        completed = subprocess.run([_program(), *arguments, "--server", self.server], capture_output=True, text=True,
                                   env=self._environment, timeout=self.timeout)
        if completed.returncode != 0:
            lines = [line for line in completed.stderr.splitlines() if line.strip()]
            message = lines[-1] if lines else f"netmc {arguments[0]} exited {completed.returncode}"
            message = message[len("netmc: error: "):] if message.startswith("netmc: error: ") else message
            raise (ValueError if completed.returncode == 2 else ServerError)(message)
        return completed.stdout

    def submit(self, **flags: Any) -> List[int]:
        """Queues a study's jobs (the keywords of netmc.sim); returns their ids at once."""
        keywords, temporary = _with_spec(flags)
        try:
            out = self._run("submit", "--quiet", *_arguments("sim", keywords))
        except ValueError as error:
            raise _spec_named(error, temporary) from None
        finally:
            if temporary:
                os.unlink(temporary)
        return [int(line) for line in out.split()]

    def watch(self, job: int) -> Study:
        """Follows job `job` until it ends; its result as a Study (no traces: a server keeps none).
        A failed or cancelled job raises ServerError with the server's reason."""
        return Study.from_json(self._run("watch", str(_job_id(job)), "--quiet", "--json", "-"))

    results = watch

    def status(self, job: Optional[int] = None) -> Dict[str, Any]:
        """The server's jobs (netmc status --json: netmc.v1.StatusReply), or one job's."""
        reply = _json.loads(self._run("status", *([str(_job_id(job))] if job is not None else []), "--json"))
        return reply

    def cancel(self, job: int) -> None:
        """Cancels job `job` (its own cancel token, or the admin token given as `token`)."""
        self._run("cancel", str(_job_id(job)))

    def jobs(self) -> Dict[str, Any]:
        """The server's job history (netmc jobs --json: netmc.v1.JobList)."""
        return _json.loads(self._run("jobs", "--json"))


def _job_id(job: Any) -> int:
    if isinstance(job, bool) or not isinstance(job, numbers.Integral) or job < 1:
        raise TypeError(f"job: expected a job id (a positive integer), got {job!r}")
    return int(job)


def _row(run: Dict[str, Any], iteration: Dict[str, Any]) -> Dict[str, Any]:
    row: Dict[str, Any] = {key: run.get(key) for key in ("label", "controller", "plant", "trajectory", "delay",
                                                          "compensation", "seed", "sample_period_s")}
    row["seed"] = int(row["seed"]) if row["seed"] is not None else None
    for key, value in iteration.items():
        if isinstance(value, list):
            if value and all(isinstance(v, (int, float)) for v in value):
                for axis, v in zip("xyz", value):
                    row[_axis_column(key, axis)] = v
        elif not isinstance(value, dict):
            row[key] = value
    return row


def _axis_column(field: str, axis: str) -> str:
    # tracking_rms_m -> tracking_rms_x_m, as the sweep CSV names them.
    for unit in ("_m", "_s"):
        if field.endswith(unit):
            return f"{field[:-len(unit)]}_{axis}{unit}"
    return f"{field}_{axis}"


def _spec_named(error: ValueError, temporary: Optional[str]) -> ValueError:
    # A dict spec's temporary file is no name a user knows: the message names the keyword.
    return ValueError(str(error).replace(temporary, "spec")) if temporary else error


def sim(*, traces: str = "on-demand", **flags: Any) -> Study:
    keywords, temporary = _with_spec(flags)
    try:
        return Study(_core.sim(_arguments("sim", keywords), traces))
    except ValueError as error:
        raise _spec_named(error, temporary) from None
    finally:
        if temporary:
            os.unlink(temporary)


def _sweep_part(arguments: List[str], index: int, count: int) -> str:
    """One part of a grid (a Dask task): the CSV part file `netmc sweep --shard K/N` writes."""
    return _core.sweep(arguments + ["--shard", f"{index}/{count}"])["csv"]


def sweep_csv(*, client: Any = None, tasks: Optional[int] = None, **grid: Any) -> str:
    """The text `netmc sweep --csv` writes for the same grid, byte for byte. With `client` (a
    distributed.Client), the grid runs as `tasks` Dask tasks (default: one per configuration, at
    most 1024), each a --shard K/N part, joined as `netmc sweep merge` joins them."""
    keywords, temporary = _with_spec(grid)
    try:
        arguments = _arguments("sweep", keywords)
        if client is None:
            return _core.sweep(arguments)["csv"]
        configurations = _core.sweep_size(arguments)
        count = min(configurations, 1024) if tasks is None else tasks
        if isinstance(count, bool) or not isinstance(count, numbers.Integral) or not 1 <= count <= 100000:
            raise ValueError(f"tasks: expected an integer of 1 to 100000, got {count!r}")
        count = min(int(count), configurations)
        arguments = arguments + ["--threads", "1"] if "threads" not in grid else arguments
        token = uuid.uuid4().hex
        futures = client.map(_sweep_part, [arguments] * count, range(1, count + 1), [count] * count,
                             key=[f"netmc-sweep-{token}-{index}-of-{count}" for index in range(1, count + 1)])
        parts = client.gather(futures)
        return _core.merge_parts([(f"task {index}/{count}", part) for index, part in enumerate(parts, start=1)])
    except ValueError as error:
        raise _spec_named(error, temporary) from None
    finally:
        if temporary:
            os.unlink(temporary)


def sweep(*, client: Any = None, tasks: Optional[int] = None, **grid: Any):
    """A pandas DataFrame of the rows `netmc sweep --csv` writes: one per configuration and iteration."""
    import pandas

    # round_trip: every number reads back as the double the CSV was written from (pandas' default
    # parser may differ in the last bit).
    return pandas.read_csv(io.StringIO(sweep_csv(client=client, tasks=tasks, **grid)), float_precision="round_trip")


sim.__doc__ = f"""Runs a study in-process, as `netmc sim` does, and returns a Study.

Keywords are the flags of `netmc sim` (a list joins with commas; a switch is True):

{_keyword_doc("sim")}

spec= also takes a dict (a job spec as `netmc sim --print-spec` prints it).
traces= how Study.trace gets an iteration's per-cycle signals: 'on-demand' (default) runs that
run again up to the iteration, recording (the run is deterministic for its seed: the same
iteration, and the study itself costs what `netmc sim` does); 'all' records every iteration while
the study runs (memory: about 1 MB per run and iteration of paper 001); 'none' keeps no way to
them.
"""

sweep.__doc__ = f"""Runs a grid as `netmc sweep` does and returns its CSV rows as a pandas DataFrame.

client= a distributed.Client runs the grid as Dask tasks on that cluster (tasks= how many parts;
each configuration runs in exactly one part, results equal to a one-process sweep bit for bit).
Keywords are the flags of `netmc sweep` (a list joins with commas, or repeats a repeatable flag):

{_keyword_doc("sweep")}
"""
