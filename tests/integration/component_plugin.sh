#!/usr/bin/env bash
# A researcher's own controller and plant through the component plugin ABI
# (control/plugin/component_plugin.hpp): netmc-dev installed into a fresh prefix, the installed
# example (share/netmc/examples/controller_plugin) copied out and built out of tree against it
# with find_package(netmc), as a researcher builds a plugin. The header and the example are
# installed; netmc::control carries the installed version (NETMC_VERSION); the plugin exports the
# entry function and none of netmc's code, and its table, read as the plain data netmc reads
# first, states plugin ABI 1 and the prefix's netmc version.
# Usage: component_plugin.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
version=$(sed -n 's/^project(netmc VERSION \([0-9.]*\).*/\1/p' "$source_dir/CMakeLists.txt")

# build_example_component_plugin PREFIX WORK_DIR: the installed example, copied to WORK_DIR/src and
# built in WORK_DIR/build; prints the plugin's path.
build_example_component_plugin() {
  cp -r "$1/share/netmc/examples/controller_plugin" "$2/src"
  cmake -S "$2/src" -B "$2/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$1" >"$2/configure.log"
  cmake --build "$2/build" >"$2/build.log"
  echo "$2/build/libexample_controller.so"
}

prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" --component dev >"$tmp/install.log"
for file in include/netmc/control/plugin/component_plugin.hpp include/netmc/control/axis/pid_axis_controller.hpp \
  include/netmc/plant/second_order_axis.hpp share/netmc/examples/controller_plugin/CMakeLists.txt \
  share/netmc/examples/controller_plugin/example_controller.cpp share/netmc/examples/controller_plugin/README.md; do
  [ -f "$prefix/$file" ] || { echo "FAIL: $file not installed"; exit 1; }
done
targets=$(ls "$prefix"/lib*/cmake/netmc/netmcTargets.cmake)
grep -q "INTERFACE_COMPILE_DEFINITIONS \"NETMC_VERSION=\\\\\"$version\\\\\"\"" "$targets" ||
  { echo "FAIL: netmc::control does not define NETMC_VERSION=\"$version\""; grep -n COMPILE_DEFINITIONS "$targets"; exit 1; }
echo "installed: control/plugin/component_plugin.hpp, the example's sources;" \
  "netmc::control defines NETMC_VERSION=\"$version\""

# The plugin that --controller plugin:PATH[:kp=..,kd=..] and --plant plugin:PATH name below.
mkdir "$tmp/example"
controller_plugin=$(build_example_component_plugin "$prefix" "$tmp/example")
[ -f "$controller_plugin" ] || { echo "FAIL: the example plugin did not build to $controller_plugin"; exit 1; }
echo "example plugin built out of tree against the installed netmc-dev: $(basename "$controller_plugin")"

objdump -T "$controller_plugin" | grep -Eq ' g +DF \.text.* netmc_component_plugin_entry$' ||
  { echo "FAIL: netmc_component_plugin_entry is not an exported function"; objdump -T "$controller_plugin"; exit 1; }
# Beyond the entry, only the C++ library's own template instances may be visible (the compiler
# exports those whatever the visibility): none of the plugin's classes, none of netmc's code.
leaked=$(nm -D --defined-only "$controller_plugin" | awk '{print $3}' | grep -v '^netmc_component_plugin_entry$' |
  c++filt | grep -v '^std::' || true)
[ -z "$leaked" ] || { echo "FAIL: the plugin exports more than its entry:"; echo "$leaked"; exit 1; }
echo "exports: netmc_component_plugin_entry (a function), and nothing of its own or of netmc's"

python3 - "$controller_plugin" "$version" <<'PY'
# The table's head as netmc reads it before anything else: uint32 abi_version, uint32 table_size,
# char netmc_version[32]; then char compiler[16].
import ctypes, sys
plugin = ctypes.CDLL(sys.argv[1], mode=ctypes.RTLD_LOCAL)
entry = plugin.netmc_component_plugin_entry
entry.restype = ctypes.c_void_p
table = entry()
abi = ctypes.c_uint32.from_address(table).value
version = ctypes.string_at(table + 8, 32).split(b"\0")[0].decode()
compiler = ctypes.string_at(table + 40, 16).split(b"\0")[0].decode()
print(f"its table: plugin ABI {abi}, netmc {version}, {compiler}")
sys.exit(0 if abi == 1 and version == sys.argv[2] else 1)
PY

# --- netmc sim, netmc sweep and netmc-server on the plugin ------------------------------------
# same_runs A B WHAT: the two results' iterations (every metric of every run) are identical; the
# runs' names differ (plugin:... against pid), so the files are compared run by run.
same_runs() {
  python3 - "$1" "$2" "$3" <<'PY'
import json, sys
a, b = (json.load(open(path)) for path in sys.argv[1:3])
runs_a, runs_b = a["runs"], b["runs"]
assert len(runs_a) == len(runs_b) > 0, f"{sys.argv[3]}: {len(runs_a)} runs against {len(runs_b)}"
for run_a, run_b in zip(runs_a, runs_b):
    if run_a["iterations"] != run_b["iterations"]:
        for it_a, it_b in zip(run_a["iterations"], run_b["iterations"]):
            for key in it_a:
                if it_a[key] != it_b.get(key):
                    sys.exit(f"FAIL {sys.argv[3]}: iteration {it_a['iteration']} {key}: {it_a[key]} against {it_b.get(key)}")
        sys.exit(f"FAIL {sys.argv[3]}: the iterations differ")
m = runs_a[-1]["iterations"][-1]
print(f"{sys.argv[3]}: identical metrics in {len(runs_a)} run(s) (last e_max {m['e_max_m'] * 1e3:.6f} mm)")
PY
}
sim() { "$netmc" sim -q --iterations 3 "$@"; }
pd="plugin:$controller_plugin:kp=540,kd=8"

# The example's PD loop is the built-in pid with ki = 0: alone, with a compensator, and with an
# axis's own gain.
sim --controller "$pd" --json "$tmp/plugin.json" >/dev/null
sim --controller pid --pid kp=540,ki=0,kd=8 --json "$tmp/pid.json" >/dev/null
same_runs "$tmp/plugin.json" "$tmp/pid.json" "--controller plugin: (PD) against pid, ki = 0"
sim --controller "$pd,y.kd=4+ilccc" --json "$tmp/plugin-ilc.json" >/dev/null
sim --controller pid+ilccc --pid kp=540,ki=0,kd=8,y.kd=4 --json "$tmp/pid-ilc.json" >/dev/null
same_runs "$tmp/plugin-ilc.json" "$tmp/pid-ilc.json" "plugin:...,y.kd=4+ilccc against pid+ilccc with y.kd=4"
# Its plant is paper 001's axis without friction.
sim --plant "plugin:$controller_plugin" --json "$tmp/plugin-plant.json" >/dev/null
sim --plant seed001:coulomb_m_s2=0 --json "$tmp/seed001.json" >/dev/null
same_runs "$tmp/plugin-plant.json" "$tmp/seed001.json" "--plant plugin: against seed001 without friction"
# The guides' headline command (docs/extending.md, your-controller-your-plant.md, the example's
# README), 10 iterations: it tracks, with the built-in pid's metrics at the same gains.
"$netmc" sim -q --iterations 10 --controller "$pd+ilccc" --plant "plugin:$controller_plugin" \
  --json "$tmp/guide.json" >/dev/null
"$netmc" sim -q --iterations 10 --controller pid+ilccc --pid kp=540,ki=0,kd=8 --plant "plugin:$controller_plugin" \
  --json "$tmp/guide-pid.json" >/dev/null
same_runs "$tmp/guide.json" "$tmp/guide-pid.json" "the guides' plugin:...:kp=540,kd=8+ilccc on the plugin plant"
python3 - "$tmp/guide.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))["runs"][0]["iterations"][-1]
assert not m.get("diverged") and m["e_max_m"] < 20e-6, m
print(f"  tracks: iteration 10 e_max {m['e_max_m'] * 1e6:.2f} um")
PY
# netmc sweep takes it as netmc sim does.
"$netmc" sweep --controller "$pd" --delay-max 1ms,4ms --duration 2s --iterations 1 --csv "$tmp/sweep.csv" \
  >"$tmp/sweep.txt"
[ "$(grep -c "plugin:" "$tmp/sweep.csv")" -eq 2 ] || { echo "FAIL: the sweep did not run the plugin twice"; cat "$tmp/sweep.txt"; exit 1; }
echo "netmc sweep ran the plugin at 2 delays"

# Refused, one message each: a build against another netmc version, another plugin ABI, a key the
# plugin does not take, a file that is not there.
refused() {  # refused WHAT EXPECTED COMMAND...
  local what=$1 expected=$2
  shift 2
  if "$@" >"$tmp/refused.out" 2>&1; then echo "FAIL: $what was accepted"; exit 1; fi
  grep -q -- "$expected" "$tmp/refused.out" || { echo "FAIL: $what: expected '$expected' in:"; cat "$tmp/refused.out"; exit 1; }
  echo "refused, $what: $(grep -m1 "error" "$tmp/refused.out" | cut -c1-200)"
}
mkdir "$tmp/old-version"
cp -r "$prefix/share/netmc/examples/controller_plugin" "$tmp/old-version/src"
sed -i '1i #include <string>\n#undef NETMC_VERSION\n#define NETMC_VERSION "0.0.9"' "$tmp/old-version/src/example_controller.cpp"
cmake -S "$tmp/old-version/src" -B "$tmp/old-version/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_FLAGS=-Wno-builtin-macro-redefined >/dev/null
cmake --build "$tmp/old-version/build" >"$tmp/old-version/build.log" 2>&1 ||
  { echo "FAIL: the version-0.0.9 build failed"; cat "$tmp/old-version/build.log"; exit 1; }
refused "a plugin built against netmc 0.0.9" "built against netmc 0.0.9" \
  "$netmc" sim -q --controller "plugin:$tmp/old-version/build/libexample_controller.so:kp=1,kd=1"
cp -r "$prefix" "$tmp/abi2"
sed -i 's/^#define NETMC_COMPONENT_PLUGIN_ABI 1$/#define NETMC_COMPONENT_PLUGIN_ABI 2/' \
  "$tmp/abi2/include/netmc/control/plugin/component_plugin.hpp"
sed -i "s#$prefix#$tmp/abi2#g" "$tmp"/abi2/lib*/cmake/netmc/*.cmake
mkdir "$tmp/abi2-example"
abi2_plugin=$(build_example_component_plugin "$tmp/abi2" "$tmp/abi2-example")
refused "a plugin of ABI 2" "plugin ABI 2" "$netmc" sim -q --controller "plugin:$abi2_plugin:kp=1,kd=1"
refused "an unknown key" "unknown key 'ki'" "$netmc" sim -q --controller "plugin:$controller_plugin:kp=1,kd=1,ki=3"
refused "a missing file" "no-such.so" "$netmc" sim -q --controller "plugin:$tmp/no-such.so:kp=1,kd=1"

# netmc-server loads only the plugins its operator named (--allow-plugin); then a lockstep run
# over DDS equals netmc sim byte for byte.
start x "$netmc_axis" --node cp-x --axes x --domain "$domain" --transport udp
start y "$netmc_axis" --node cp-y --axes y --domain "$domain" --transport udp
start server "$netmc_server" --listen 127.0.0.1:0 --domain "$domain" --transport udp \
  --allow-plugin "$controller_plugin"
port=$(server_port 127.0.0.1)
refused "a plugin the server was not given" "not a file this server loads" \
  "$netmc" run --server "127.0.0.1:$port" -q --controller "plugin:$tmp/old-version/build/libexample_controller.so:kp=1,kd=1"
"$netmc" run --server "127.0.0.1:$port" --quiet --iterations 3 --controller "$pd+ilccc" --json "$tmp/dds.json" >/dev/null
sim --controller "$pd+ilccc" --json "$tmp/sim.json" >/dev/null
same_json "$tmp/sim.json" "$tmp/dds.json" "plugin controller, lockstep over DDS,"
