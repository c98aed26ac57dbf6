#!/usr/bin/env bash
# What a lab installs: `cmake --install` into a fresh prefix puts the three programs (each
# answers --version with the project's version), the pure libraries with their headers and CMake
# package, the systemd units (naming the installed programs; systemd-analyze verifies them) and
# the examples in place; a project of its own (tests/install/consumer) finds netmc with
# find_package, links netmc::control without Fast DDS or protobuf, and its ADRC loop settles.
# The installed example drive plugin builds out of tree against the prefix (netmc::drive_plugin)
# and exports the ABI's entry object and nothing else; the installed ABI header compiles as C and C++.
# The example specs are one per preset and run, and so does the example FMU. Then CPack's two
# .debs: netmc (programs, units, examples; its dependencies Debian's runtime packages) and
# netmc-dev (libraries, headers), under /usr.
# Usage: install_package.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
version=$(sed -n 's/^project(netmc VERSION \([0-9.]*\).*/\1/p' "$source_dir/CMakeLists.txt")
prefix=$tmp/prefix

cmake --install "$build" --prefix "$prefix" >"$tmp/install.log"
for program in netmc netmc-server netmc-axis netmc-drive-emulator; do
  out=$("$prefix/bin/$program" --version)
  [ "$out" = "$program $version" ] || { echo "FAIL: $program --version said '$out'"; exit 1; }
done
echo "installed: netmc, netmc-server, netmc-axis, netmc-drive-emulator --version: $version"
for file in include/netmc/control/axis/adrc_controller.hpp include/netmc/plant/plant_catalog.hpp \
  include/netmc/netsim/delay_model.hpp include/netmc/drive_plugin.h \
  share/netmc/examples/drive_plugin/example_drive.c share/netmc/examples/etc-netmc/server.env \
  share/netmc/examples/dds-profiles/udp_only.xml share/netmc/examples/drive-maps/default-map.json \
  share/netmc/examples/fmu_axis/ball_screw_axis.fmu share/doc/netmc/LICENSE; do
  [ -f "$prefix/$file" ] || { echo "FAIL: $file not installed"; exit 1; }
done
# The example specs: one per preset, each what `--spec` reads, giving the preset's first run.
presets=$("$prefix/bin/netmc" sim --list-presets)
[ "$(ls "$prefix/share/netmc/examples/specs" | sort)" = "$(for p in $presets; do echo "$p.json"; done | sort)" ] ||
  { echo "FAIL: the example specs are not one per preset"; ls "$prefix/share/netmc/examples/specs"; exit 1; }
"$prefix/bin/netmc" sim -q --spec "$prefix/share/netmc/examples/specs/seed001.json" --iterations 2 --json "$tmp/spec.json" >/dev/null
"$prefix/bin/netmc" sim -q --preset seed001 --controller adrc --iterations 2 --json "$tmp/preset.json" >/dev/null
cmp -s "$tmp/spec.json" "$tmp/preset.json" ||
  { echo "FAIL: the installed seed001 spec does not run as the preset's first run"; diff "$tmp/spec.json" "$tmp/preset.json" | head; exit 1; }
echo "example specs: $(echo $presets | wc -w), one per preset; seed001.json runs as netmc sim --preset seed001 --controller adrc"
"$prefix/bin/netmc" sim -q --iterations 2 --plant "fmu:$prefix/share/netmc/examples/fmu_axis/ball_screw_axis.fmu:velocity=v" \
  --json "$tmp/fmu.json" >/dev/null
echo "the installed example FMU runs: netmc sim --plant fmu:PREFIX/share/netmc/examples/fmu_axis/ball_screw_axis.fmu"
config=$(find "$prefix" -name netmcConfig.cmake)
[ -n "$config" ] || { echo "FAIL: no netmcConfig.cmake"; exit 1; }
units=$prefix/lib/systemd/system
grep -q "^ExecStart=$prefix/bin/netmc-server " "$units/netmc-server.service" &&
  grep -q "^ExecStart=$prefix/bin/netmc-axis --node %i " "$units/netmc-axis@.service" ||
  { echo "FAIL: the units do not name the installed programs"; cat "$units"/*; exit 1; }
if command -v systemd-analyze >/dev/null; then
  cp "$units/netmc-axis@.service" "$units/netmc-axis@lab1.service"
  (cd "$units" && SYSTEMD_LOG_LEVEL=warning systemd-analyze verify --man=no netmc-server.service netmc-axis@lab1.service) \
    2>&1 | tee "$tmp/verify.log"
  ! grep -v "^$" "$tmp/verify.log" | grep -q . || { echo "FAIL: systemd-analyze verify complained"; exit 1; }
  echo "systemd-analyze verify: netmc-server.service, netmc-axis@.service: no complaint"
  # The same with the example drop-ins (credentials for the keys and the admin token) in place.
  cp -r "$prefix/share/netmc/examples/systemd/"*.service.d "$units/"
  [ "$(ls "$units"/*.service.d/*.conf | wc -l)" = 3 ] || { echo "FAIL: expected 3 example drop-ins"; ls -R "$units"; exit 1; }
  (cd "$units" && SYSTEMD_LOG_LEVEL=warning systemd-analyze verify --man=no netmc-server.service netmc-axis@lab1.service) \
    2>&1 | tee "$tmp/verify.log"
  ! grep -v "^$" "$tmp/verify.log" | grep -q . || { echo "FAIL: systemd-analyze verify complained of a drop-in"; exit 1; }
  # A drop-in systemd cannot read must be seen to fail, or the check above proves nothing.
  echo "ExecStart=" >>"$units/netmc-server.service.d/security.conf"   # clears the command: refused
  ! (cd "$units" && SYSTEMD_LOG_LEVEL=warning systemd-analyze verify --man=no netmc-server.service) >/dev/null 2>&1 ||
    { echo "FAIL: systemd-analyze verify did not read the drop-ins"; exit 1; }
  rm -r "$units"/*.service.d "$units/netmc-axis@lab1.service"
  echo "systemd-analyze verify with the example drop-ins (security, admin token): no complaint"
fi

cmake -S "$source_dir/tests/install/consumer" -B "$tmp/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >"$tmp/consumer-configure.log"
cmake --build "$tmp/consumer" >"$tmp/consumer-build.log"
if grep -Eq "fastrtps|fastcdr|protobuf" "$tmp/consumer/build.ninja"; then
  echo "FAIL: the consumer's build names Fast DDS or protobuf"; exit 1
fi
"$tmp/consumer/adrc_step"
echo "find_package(netmc) + netmc::control: built without Fast DDS or protobuf, and ran"

# A lab's drive plugin: the installed example, copied out and built against the prefix as a lab
# builds its own. Its path ($drive_plugin) is what --drive plugin:PATH names.
drive_plugin=$tmp/drive-plugin/libexample_drive.so
cp -r "$prefix/share/netmc/examples/drive_plugin" "$tmp/drive-plugin-src"
cmake -S "$tmp/drive-plugin-src" -B "$tmp/drive-plugin" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >"$tmp/drive-plugin-configure.log"
cmake --build "$tmp/drive-plugin" >"$tmp/drive-plugin-build.log"
[ -f "$drive_plugin" ] || { echo "FAIL: the example drive plugin did not build to $drive_plugin"; exit 1; }
exported=$(nm -D --defined-only "$drive_plugin" | awk '{print $3}' | tr '\n' ' ')
[ "$exported" = "netmc_drive_plugin " ] ||
  { echo "FAIL: the example plugin exports '$exported', not netmc_drive_plugin alone"; exit 1; }
objdump -T "$drive_plugin" | grep -Eq ' DO .* netmc_drive_plugin$' ||
  { echo "FAIL: netmc_drive_plugin is not an exported data object"; objdump -T "$drive_plugin"; exit 1; }
# The ABI header alone, from plain C (C99 and C11) and from C++, warnings as errors.
cat >"$tmp/abi_check.c" <<'CHECK'
#include <netmc/drive_plugin.h>
typedef char abi_version_is_1[NETMC_DRIVE_PLUGIN_ABI_VERSION == 1 ? 1 : -1];
const netmc_drive_plugin_table* entry_of(const netmc_drive_plugin_table* table) { return table; }
CHECK
for std in c99 c11; do
  cc -std=$std -Wall -Wextra -Wpedantic -Werror -I"$prefix/include" -c "$tmp/abi_check.c" -o "$tmp/abi_check.o"
done
c++ -x c++ -std=c++17 -Wall -Wextra -Wpedantic -Werror -I"$prefix/include" -c "$tmp/abi_check.c" -o "$tmp/abi_check.o"
echo "drive plugin: the installed example built against the prefix, exports netmc_drive_plugin only;" \
  "<netmc/drive_plugin.h> compiles as C99, C11 and C++17"

cpack --config "$build/CPackConfig.cmake" -B "$tmp/package" >"$tmp/cpack.log" 2>&1 ||
  { cat "$tmp/cpack.log"; exit 1; }
deb=$(ls "$tmp/package"/netmc_"$version"_*.deb)
dev=$(ls "$tmp/package"/netmc-dev_"$version"_*.deb)
depends=$(dpkg-deb -f "$deb" Depends)
echo "$(basename "$deb"): $(du -k "$deb" | cut -f1) KiB, Depends: $depends"
for package in libfastrtps2.9 libprotobuf32 libmodbus5 libc6 libstdc++6; do
  [[ "$depends" == *"$package"* ]] || { echo "FAIL: the .deb does not depend on $package"; exit 1; }
done
dpkg-deb -c "$deb" >"$tmp/contents"
for file in ./usr/bin/netmc ./usr/bin/netmc-server ./usr/bin/netmc-axis ./usr/bin/netmc-drive-emulator \
  ./usr/lib/systemd/system/netmc-server.service \
  ./usr/share/netmc/examples/specs/seed001.json ./usr/share/netmc/examples/fmu_axis/ball_screw_axis.fmu; do
  grep -q " $file\$" "$tmp/contents" || { echo "FAIL: $file not in the .deb"; exit 1; }
done
! grep -q "/usr/include/" "$tmp/contents" || { echo "FAIL: headers in the runtime package"; exit 1; }
dpkg-deb --fsys-tarfile "$deb" | tar -xO ./usr/lib/systemd/system/netmc-axis@.service >"$tmp/unit"
grep -q "^ExecStart=/usr/bin/netmc-axis " "$tmp/unit" ||
  { echo "FAIL: the packaged unit does not name /usr/bin/netmc-axis"; exit 1; }
dpkg-deb -c "$dev" >"$tmp/dev-contents"
grep -q " ./usr/include/netmc/control/axis/adrc_controller.hpp$" "$tmp/dev-contents" &&
  grep -q " ./usr/include/netmc/drive_plugin.h$" "$tmp/dev-contents" &&
  grep -q " ./usr/share/netmc/examples/drive_plugin/example_drive.c$" "$tmp/dev-contents" &&
  [[ "$(dpkg-deb -f "$dev" Depends)" == *libeigen3-dev* ]] ||
  { echo "FAIL: netmc-dev lacks the headers, the example drive plugin or the Eigen dependency"; exit 1; }
echo "$(basename "$dev"): $(du -k "$dev" | cut -f1) KiB, Depends: $(dpkg-deb -f "$dev" Depends)"
echo "the .debs hold the programs, units and examples (netmc) and the libraries and headers (netmc-dev) under /usr"
