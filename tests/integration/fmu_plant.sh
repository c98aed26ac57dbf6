#!/usr/bin/env bash
# FMU plants (FMI 2.0 co-simulation) in netmc sim, netmc sweep and under netmc-axis: the test FMU
# of paper 001's axis, built from C by the test suite (tests/fmu), against the built-in plant it
# re-implements: within 1e-6 relative on paper 001's plant (friction), within 1e-9 on the linear
# axis (no friction); a realtime job on two netmc-axis nodes hosting the FMU runs and learns; bad
# FMUs are refused with one message each, and a node refuses an FMU plant without limits.
# Usage: fmu_plant.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
fmus=$build/tests/fmu
# The FMU's parameters default to seed001's X axis; its Y axis takes its own (a2, b, friction).
fmu="fmu:$fmus/seed001_axis.fmu:velocity=v,y.a2=-10,y.b=10,y.coulomb=0.085"

# agree A B WHAT BOUND: every run's e_max, e_sum, e_rms, tracking and command RMS within BOUND
# relative.
agree() {
  python3 - "$@" <<'PY'
import json, sys
a, b = (json.load(open(path)) for path in sys.argv[1:3])
what, bound = sys.argv[3], float(sys.argv[4])
worst, count = 0.0, 0
for run_a, run_b in zip(a["runs"], b["runs"], strict=True):
    for it_a, it_b in zip(run_a["iterations"], run_b["iterations"], strict=True):
        pairs = [(it_a[k], it_b[k]) for k in ("e_max_m", "e_sum_m", "e_rms_m")]
        for k in ("tracking_max_m", "command_rms"):
            pairs += list(zip(it_a[k], it_b[k], strict=True))
        for x, y in pairs:
            worst = max(worst, abs(x - y) / max(abs(y), 1e-300))
            count += 1
print(f"{what}: {count} metrics, largest relative difference {worst:.3g} (bound {bound:g})")
sys.exit(0 if worst <= bound else 1)
PY
}

"$netmc" sim -q --controller adrc+ilccc --plant "$fmu" --json "$tmp/fmu.json" >/dev/null
"$netmc" sim -q --controller adrc+ilccc --plant seed001 --json "$tmp/seed001.json" >/dev/null
agree "$tmp/fmu.json" "$tmp/seed001.json" "netmc sim, adrc+ilccc, 20 iterations: FMU against seed001" 1e-6
linear="fmu:$fmus/seed001_axis.fmu:velocity=v,y.a2=-10,y.b=10,coulomb=0"
"$netmc" sim -q --iterations 3 --plant "$linear" --json "$tmp/fmu-linear.json" >/dev/null
"$netmc" sim -q --iterations 3 --plant seed001:coulomb_m_s2=0 --json "$tmp/linear.json" >/dev/null
agree "$tmp/fmu-linear.json" "$tmp/linear.json" "netmc sim, paper 001's four controllers: FMU against the linear axis" 1e-9
"$netmc" sweep --plant "$fmu" --delay-max 1ms,4ms --duration 2s --iterations 1 --csv "$tmp/sweep.csv" >/dev/null
[ "$(grep -c "seed001_axis.fmu" "$tmp/sweep.csv")" -eq 8 ] || { echo "FAIL: the sweep did not run the FMU"; exit 1; }
echo "netmc sweep ran the FMU plant in 8 configurations"

# Refused, one message each.
refused() {  # refused WHAT EXPECTED COMMAND...
  local what=$1 expected=$2
  shift 2
  if "$@" >"$tmp/refused.out" 2>&1; then echo "FAIL: $what was accepted"; exit 1; fi
  [ "$(grep -c "error" "$tmp/refused.out")" -eq 1 ] || { echo "FAIL: $what: not one message:"; cat "$tmp/refused.out"; exit 1; }
  grep -q -- "$expected" "$tmp/refused.out" || { echo "FAIL: $what: expected '$expected' in:"; cat "$tmp/refused.out"; exit 1; }
  echo "refused, $what: $(cut -c1-220 "$tmp/refused.out")"
}
refused "a zip with no linux64 binary" "no binary for 64-bit Linux" "$netmc" sim -q --plant "fmu:$fmus/no_binary.fmu"
refused "FMI 1.0" "fmiVersion is '1.0'" "$netmc" sim -q --plant "fmu:$fmus/fmi1_version.fmu"
refused "model exchange only" "model exchange" "$netmc" sim -q --plant "fmu:$fmus/model_exchange.fmu"
refused "a missing variable" "nope" "$netmc" sim -q --plant "fmu:$fmus/seed001_axis.fmu:output=nope"
refused "a missing symbol" "fmi2DoStep" "$netmc" sim -q --plant "fmu:$fmus/no_do_step.fmu"
refused "not a zip" "not_a_zip.fmu" "$netmc" sim -q --plant "fmu:$fmus/not_a_zip.fmu"
refused "a node without limits" "needs a command limit" \
  "$netmc_axis" --node f-x --axes x --plant "$fmu" --clock realtime --domain "$domain"

# A realtime job on two nodes hosting the FMU (the server opens no FMU: its plant is the nodes').
# Watchdog 200 ms, not 50: a host stall is not this test's subject (chaos_starvation.sh's is).
limits=(--command-limit 1 --position-window -0.1:0.2 --velocity-limit 0.5 --watchdog 200)
for axis in x y; do
  start "$axis" "$netmc_axis" --node fmu-$axis --axes $axis --clock realtime --plant "$fmu" \
    "${limits[@]}" --domain "$domain" --transport udp
done
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
port=$(server_port 127.0.0.1)
"$netmc" run --server "127.0.0.1:$port" --clock realtime --controller adrc+ilccc --plant "$fmu" --iterations 5 \
  --json "$tmp/rt.json" >"$tmp/rt.txt"
python3 - "$tmp/rt.json" <<'PY'
import json, sys
its = json.load(open(sys.argv[1]))["runs"][0]["iterations"]
assert len(its) == 5 and not any(it["diverged"] or it.get("did_not_follow") for it in its), its
first, last = its[0]["e_sum_m"], its[-1]["e_sum_m"]
misses = sum(it["deadline_misses"] for it in its)
print(f"realtime on FMU plants: e_sum {first * 1e3:.2f} -> {last * 1e3:.2f} mm in 5 iterations "
      f"({(1 - last / first) * 100:.1f} % less), e_max {its[-1]['e_max_m'] * 1e6:.1f} um, {misses} deadline misses")
sys.exit(0 if last < 0.5 * first else 1)
PY
