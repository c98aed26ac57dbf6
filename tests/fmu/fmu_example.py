#!/usr/bin/python3
"""The docs' FMU commands run as written on the example FMU the build makes (examples/fmu_axis).

Every ```sh block of README.md, docs/ and examples/fmu_axis/README.md is read; a command that
names an FMU (fmu:PATH) must name the example, by its installed path or its build-tree path, and
a page that gives the installed path gives the build-tree one too. Each `netmc sim` and `netmc
sweep` line then runs as written, with the program and the FMU of this build (cwd a scratch
directory): it must succeed, and every run of its table must be stable, follow the reference and
keep e_max under E_MAX_BOUND_MM. Another command naming the FMU (netmc-axis) has its plant text
run by `netmc sim --iterations 1`. `netmc sim --plant-parameters fmu:PATH` lists the example's
parameters, with their units.

Usage: fmu_example.py BUILD_DIR SOURCE_DIR
"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

INSTALLED = "/usr/share/netmc/examples/fmu_axis/ball_screw_axis.fmu"
BUILD_RELATIVE = "build/examples/fmu_axis/ball_screw_axis.fmu"
# paper 001's four controllers on the example measure 0.131 mm at most (adrc); a run that lost
# the contour, or an FMU that no longer tracks with the default gains, is far above.
E_MAX_BOUND_MM = 0.2
PARAMETERS = {"mass": "kg", "rotor_inertia": "kg.m2", "screw_lead": "m", "torque_constant": "N.m/A",
              "damping": "N.s/m", "coulomb": "N", "coulomb_velocity": "m/s", "x0": "m", "v0": "m/s"}
FMU_TEXT = re.compile(r"fmu:(\S+?\.fmu)(?=[:\s]|$)")
FAILURES = []


def fail(message):
    FAILURES.append(message)
    print("FAIL: " + message)


def sh_commands(path):
    """(line number, command) of each ```sh block, continuation lines joined, comments kept."""
    out, block, start, pending = [], False, 0, ""
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if line.startswith("```"):
                block = line.strip() == "```sh"
                continue
            if not block:
                continue
            if not pending:
                start = number
            if line.rstrip().endswith("\\"):
                pending += line.rstrip()[:-1] + " "
                continue
            out.append((start, pending + line.strip()))
            pending = ""
    return out


def table_rows(output, sweep):
    """(name, e_max in mm, rest of the row) of each run of netmc sim's or netmc sweep's table."""
    rows, inside = [], False
    for line in output.splitlines():
        if line.startswith("run ") or line.startswith("base "):
            inside = True
            continue
        if inside and not line.strip():
            if rows:
                break
            continue
        if inside:
            fields = line.split()
            if sweep:
                # base, delay bound, then one e_max per controller; a flag (u * n +) is no number
                rows += [(f"{fields[0]} {fields[1]} ms", cell, line) for cell in fields[2:]]
            else:
                rows.append((fields[0], fields[1], line))
    return rows


def check_runs(what, output, sweep):
    rows = table_rows(output, sweep)
    if not rows:
        fail(f"{what}: no table in its output:\n{output}")
    for name, e_max, rest in rows:
        try:
            value = float(e_max)
        except ValueError:
            fail(f"{what}: {name}: {rest.strip()}")
            continue
        if "did not follow" in rest or not value < E_MAX_BOUND_MM:
            fail(f"{what}: {name}: e_max {value} mm (bound {E_MAX_BOUND_MM}), {rest.strip()}")
    if rows:
        worst = max((float(r[1]) for r in rows if re.fullmatch(r"[\d.]+", r[1])), default=float("nan"))
        print(f"  {len(rows)} runs, largest e_max {worst} mm (bound {E_MAX_BOUND_MM} mm)")


def main():
    build, source = (os.path.abspath(p) for p in sys.argv[1:3])
    netmc = os.path.join(build, "client", "netmc")
    fmu = os.path.join(build, "examples", "fmu_axis", "ball_screw_axis.fmu")
    scratch = tempfile.mkdtemp()
    try:
        return run_checks(netmc, fmu, source, scratch)
    finally:
        shutil.rmtree(scratch)


def run_checks(netmc, fmu, source, scratch):
    pages = [os.path.join(source, "README.md"), os.path.join(source, "examples", "fmu_axis", "README.md")]
    pages += sorted(glob.glob(os.path.join(source, "docs", "**", "*.md"), recursive=True))

    ran = 0
    for page in pages:
        relative = os.path.relpath(page, source)
        with open(page, encoding="utf-8") as f:
            text = f.read()
        if INSTALLED in text and BUILD_RELATIVE not in text:
            fail(f"{relative}: gives the example's installed path, not its build-tree path {BUILD_RELATIVE}")
        variables = {}
        for number, command in sh_commands(page):
            if "fmu" not in command:
                continue
            words = shlex.split(command, comments=True)
            if len(words) == 1 and re.fullmatch(r"\w+=\S+", words[0]):
                name, value = words[0].split("=", 1)
                variables[name] = value
                continue
            expanded = [re.sub(r"\$(\w+)", lambda m: variables.get(m.group(1), m.group(0)), w) for w in words]
            texts = [m for w in expanded for m in FMU_TEXT.findall(w)]
            if not texts:
                continue
            where = f"{relative}:{number}"
            for path in texts:
                if path not in (INSTALLED, BUILD_RELATIVE):
                    fail(f"{where}: names the FMU {path}, which netmc does not ship "
                         f"(the example: {INSTALLED}, in a build tree {BUILD_RELATIVE})")
            here = [w.replace(INSTALLED, fmu).replace("fmu:" + BUILD_RELATIVE, "fmu:" + fmu) for w in expanded]
            program = os.path.basename(here[0])
            if program == "netmc" and len(here) > 1 and here[1] in ("sim", "sweep"):
                argv = [netmc] + here[1:]
                what = f"{where}: {' '.join(words)}"
            else:
                plant = next(w for w in here if w.startswith("fmu:"))
                argv = [netmc, "sim", "--iterations", "1", "--plant", plant]
                what = f"{where}: the plant of {program}: {plant}"
            print(f"{what}")
            result = subprocess.run(argv, cwd=scratch, capture_output=True, text=True, check=False)
            ran += 1
            if result.returncode != 0:
                fail(f"{what}: exit {result.returncode}: {result.stderr.strip()}")
                continue
            if "--plant-parameters" in argv:
                listed = set(re.findall(r"^  (\w+) ", result.stdout, re.MULTILINE))
                if listed != set(PARAMETERS):
                    fail(f"{what}: lists {sorted(listed)}, expected {sorted(PARAMETERS)}")
                continue
            check_runs(what, result.stdout, argv[1] == "sweep")
    if ran < 5:
        fail(f"only {ran} commands name the example FMU in the docs (expected 5 or more)")

    # The parameters, their units and start values, as netmc reads them from the FMU.
    result = subprocess.run([netmc, "sim", "--plant-parameters", "fmu:" + fmu], cwd=scratch, capture_output=True,
                            text=True, check=False)
    for name, unit in PARAMETERS.items():
        if not re.search(rf"^  {name} +FMU parameter \({re.escape(unit)}\); \S+$", result.stdout, re.MULTILINE):
            fail(f"netmc sim --plant-parameters: no line for {name} ({unit}) in:\n{result.stdout}{result.stderr}")
    print(f"netmc sim --plant-parameters fmu:{fmu}: {len(PARAMETERS)} parameters with their units")
    print(f"{ran} commands run; {len(FAILURES)} failures")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
