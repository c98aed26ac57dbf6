#!/usr/bin/env bash
# A researcher's own controller and plant through the component plugin ABI
# (control/plugin/component_plugin.hpp): netmc-dev installed into a fresh prefix, the installed
# example (share/netmc/examples/controller_plugin) copied out and built out of tree against it
# with find_package(netmc), as a researcher builds a plugin. The header and the example are
# installed; netmc::control carries the installed version (NETMC_VERSION); the plugin exports the
# entry function and none of netmc's code, and its table, read as the plain data netmc reads
# first, states plugin ABI 1 and the prefix's netmc version.
# Usage: component_plugin.sh BUILD_DIR
set -euo pipefail
trap 'echo "$0: failed at line $LINENO (exit $?)"' ERR
build=$(cd "$1" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
source "$(dirname "$0")/lib.sh"
version=$(sed -n 's/^project(netmc VERSION \([0-9.]*\).*/\1/p' "$source_dir/CMakeLists.txt")
netmc=$build/client/netmc  # for the netmc sim part at the end

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

# --- netmc sim on the plugin ---------------------------------------------------------------
# Added with --controller plugin: / --plant plugin: in the CLI: "$netmc" sim with
#   --controller "plugin:$controller_plugin:kp=..,kd=.." --plant "plugin:$controller_plugin"
# against --controller pid (ki = 0, same kp and kd) on --plant seed001:coulomb_m_s2=0, compared
# with same_json (lib.sh): the example is that loop and that plant, so the JSON is identical.
