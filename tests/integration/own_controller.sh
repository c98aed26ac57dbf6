#!/usr/bin/env bash
# A controller and a plant added as a researcher adds them: tests/components/test_pd_controller.cpp
# (the law and its descriptor) and test_mass_plant.cpp (the model and its descriptor), each with
# one registration line (server/job/controllers/registered_controllers.inc,
# plant/models/registered_plants.inc), in a build with -DNETMC_TEST_COMPONENTS=ON. The law must
# show in netmc sim --help (its name and its gains flag), the plant in --list-plants and
# --plant-parameters; both run from a spec file (per-axis gains, a plant parameter), and give the
# same JSON, byte for byte, over DDS in lockstep (the axis nodes hosting test-mass) as netmc sim
# in-process.
# Usage: own_controller.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"

"$netmc" sim --help >"$tmp/help.txt"
grep -q -- "--test-pd" "$tmp/help.txt" || { echo "FAIL: --test-pd is not in netmc sim --help"; exit 1; }
grep -q -- "test-pd" <(grep -- "--controller" "$tmp/help.txt") ||
  { echo "FAIL: test-pd is not among --controller's names"; grep -- "--controller" "$tmp/help.txt"; exit 1; }
"$netmc" sim --list-controllers | grep -q '^| `test-pd` | axis law | `--test-pd` |' ||
  { echo "FAIL: test-pd is not in netmc sim --list-controllers"; exit 1; }
echo "netmc sim --help: test-pd among the controllers, --test-pd among the flags"
"$netmc" sim --list-plants | grep -q '^| `test-mass` | .* | N | -0.1 .. 0.2 | 5 N | `mass_kg`, `damping_n_s_m` |$' ||
  { echo "FAIL: test-mass is not in netmc sim --list-plants"; "$netmc" sim --list-plants; exit 1; }
"$netmc" sim --plant-parameters test-mass | grep -q "^  mass_kg  *m, moving mass (kg); 0.05$" ||
  { echo "FAIL: netmc sim --plant-parameters test-mass"; exit 1; }
echo "netmc sim --list-plants and --plant-parameters: test-mass, its unit and keys"

cat >"$tmp/spec.json" <<'JSON'
{
  "name": "own law",
  "trajectory": {"circle": {"radius_m": 0.01, "center_x_m": 0.05, "center_y_m": 0.05, "period_s": 8}},
  "downlink": {"delay": {"uniform": {"min_s": 0.0003, "max_s": 0.0008}}},
  "controller": {"name": "test-pd+ilccc",
                 "gains": {"test_pd": {"values": {"kp": 400}, "axes": {"y": {"values": {"kd": 6}}}},
                           "ilccc": {"values": {"kcp": 30}}}},
  "iterations": 3
}
JSON
"$netmc" sim --spec "$tmp/spec.json" --json "$tmp/sim.json" >"$tmp/sim.txt"
cat "$tmp/sim.txt"
grep -q "test-pd kp=400 kd=8 x test-pd kp=400 kd=6 + ilccc(kcp=30" "$tmp/sim.json" ||
  { echo "FAIL: the spec's gains did not reach the law"; grep controller_detail "$tmp/sim.json"; exit 1; }
# A key the law does not declare is refused, naming the field.
sed 's/"kp": 400/"ki": 400/' "$tmp/spec.json" >"$tmp/bad.json"
if "$netmc" sim --spec "$tmp/bad.json" >"$tmp/bad.txt" 2>&1; then echo "FAIL: an unknown gain was accepted"; exit 1; fi
grep -q "controller.gains.test_pd.ki: unknown key (expected one of: kp, kd)" "$tmp/bad.txt" ||
  { echo "FAIL: unexpected message:"; cat "$tmp/bad.txt"; exit 1; }
echo "an unknown gain is refused: $(cat "$tmp/bad.txt")"

start x "$netmc_axis" --node own-x --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node own-y --axes y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
port=$(server_port 127.0.0.1)
"$netmc" run --server "127.0.0.1:$port" --quiet --spec "$tmp/spec.json" --json "$tmp/dds.json" >/dev/null
same_json "$tmp/sim.json" "$tmp/dds.json" "the test suite's own controller, lockstep over DDS,"

# The test suite's own plant under its own law: x'' = 20 u - 20 x' is seed001's X without friction,
# so test-pd's gains hold; a heavier Y axis (mass_kg 0.06) on nodes that host test-mass.
python3 - "$tmp/spec.json" "$tmp/plant-spec.json" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
spec["plant"] = "test-mass"
spec["plant_axes"] = [{"axis": "y", "parameters": [{"key": "mass_kg", "value": 0.06}]}]
json.dump(spec, open(sys.argv[2], "w"))
PY
"$netmc" sim --spec "$tmp/plant-spec.json" --json "$tmp/plant-sim.json" >"$tmp/plant-sim.txt" ||
  { echo "FAIL: netmc sim with test-mass"; cat "$tmp/plant-sim.txt"; exit 1; }
grep -q '"plant": "test-mass' "$tmp/plant-sim.json" || { echo "FAIL: the run is not on test-mass"; exit 1; }
lab_stop x
lab_stop y
start px "$netmc_axis" --node own-px --axes x --plant test-mass --domain "$domain" --transport udp
start py "$netmc_axis" --node own-py --axes y --plant test-mass --domain "$domain" --transport udp
for _ in $(seq 100); do grep -q serving "$tmp/px.log" && grep -q serving "$tmp/py.log" && break; sleep 0.1; done
"$netmc" run --server "127.0.0.1:$port" --quiet --spec "$tmp/plant-spec.json" --json "$tmp/plant-dds.json" >/dev/null ||
  { echo "FAIL: the job on test-mass over DDS"; tail -n 5 "$tmp/px.log" "$tmp/server.log"; exit 1; }
same_json "$tmp/plant-sim.json" "$tmp/plant-dds.json" "the test suite's own plant (test-mass), lockstep over DDS,"
