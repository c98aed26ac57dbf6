#!/usr/bin/env bash
# A controller added as a researcher adds one: tests/components/test_pd_controller.cpp (the law
# and its descriptor) and one registration line (server/job/controllers/registered_controllers.inc),
# in a build with -DNETMC_TEST_COMPONENTS=ON. It must show in netmc sim --help (its name and its
# gains flag), run from a spec file with per-axis gains, and give the same JSON, byte for byte,
# over DDS in lockstep as netmc sim in-process.
# Usage: own_controller.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"

"$netmc" sim --help >"$tmp/help.txt"
grep -q -- "--test-pd" "$tmp/help.txt" || { echo "FAIL: --test-pd is not in netmc sim --help"; exit 1; }
grep -q -- "test-pd" <(grep -- "--controller" "$tmp/help.txt") ||
  { echo "FAIL: test-pd is not among --controller's names"; grep -- "--controller" "$tmp/help.txt"; exit 1; }
"$netmc" sim --list-controllers | grep -q '^| `test-pd` | axis law | `--test-pd` |' ||
  { echo "FAIL: test-pd is not in netmc sim --list-controllers"; exit 1; }
echo "netmc sim --help: test-pd among the controllers, --test-pd among the flags"

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
