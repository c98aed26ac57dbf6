#!/usr/bin/env bash
# Delay compensation on the wall clock: two netmc-axis nodes and netmc-server on loopback, a
# realtime job behind a constant 20 ms downlink (four periods, where every uncompensated run of
# paper 001's study diverges) with --compensate predictor. The run must stay stable with e_max
# within 1.2 x of netmc sim with the same flags. Extra flags (e.g. another --compensate, a loss)
# replace the compensator and add to the study's.
# Usage: realtime_compensated.sh BUILD_DIR [STUDY FLAGS...]
source "$(dirname "$0")/lib.sh" "$@"
shift
extra=("$@")
[ ${#extra[@]} -gt 0 ] || extra=(--compensate predictor)

for axis in x y; do
  # Command limit 20 (the rated input is 1) and watchdog 200 ms: a host stall makes ADRC ask more
  # than the rated 1 for a cycle (1.0075 seen with packets, 5.003 once in CI), and neither that trip
  # nor the watchdog is what is tested here.
  start "$axis" "$netmc_axis" --node rtc-$axis --axes $axis --clock realtime --command-limit 20 --watchdog 200 \
    --domain "$domain" --transport udp
done
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp
port=$(server_port 127.0.0.1)

flags=(--controller adrc --iterations 1 --delay constant:20ms "${extra[@]}")
"$netmc" run --server "127.0.0.1:$port" --clock realtime --quiet "${flags[@]}" --json "$tmp/rt.json"
"$netmc" sim --quiet "${flags[@]}" --json "$tmp/sim.json" >/dev/null
python3 - "$tmp/rt.json" "$tmp/sim.json" <<'PY'
import json, sys
realtime, sim = (json.load(open(path))["runs"][0]["iterations"][-1] for path in sys.argv[1:3])
if realtime.get("diverged") or sim.get("diverged"):
    sys.exit(f"FAIL: a compensated run diverged (realtime {realtime.get('diverged')}, sim {sim.get('diverged')})")
ratio = realtime["e_max_m"] / sim["e_max_m"]
covered = f", {realtime['horizon_cycles']} cycles played from a horizon, {realtime['held_cycles']} held" if "horizon_cycles" in realtime else ""
print(f"realtime, 20 ms downlink, {json.load(open(sys.argv[1]))['runs'][0]['compensation']}: e_max {realtime['e_max_m'] * 1e6:.1f} um, netmc sim "
      f"{sim['e_max_m'] * 1e6:.1f} um (x {ratio:.3f}); loop delay mean {realtime['tau_mean_s'] * 1e3:.2f} ms, "
      f"feedback age mean {realtime['feedback_age_mean_s'] * 1e3:.2f} ms, max {realtime['feedback_age_max_s'] * 1e3:.2f} ms{covered}")
sys.exit(0 if ratio <= 1.2 else "FAIL: realtime e_max beyond 1.2 x netmc sim's")
PY
