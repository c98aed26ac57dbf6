#!/usr/bin/env bash
# All tests: install dependencies, build with warnings as errors, run every ctest label.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# The test build carries the test suite's own controller (tests/components).
bash scripts/build.sh -DNETMC_WERROR=ON -DNETMC_TEST_COMPONENTS=ON
# Tests run with a private HOME and XDG_STATE_HOME (build/test-home, set by CMakeLists.txt): the
# user's own may gain no file while they run.
marker=$(mktemp)
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600
written=$(find "$HOME/.local" "$HOME/.config" -type f -newer "$marker" 2>/dev/null | head -20 || true)
rm -f "$marker"
if [ -n "$written" ]; then
  echo "FAIL: the tests wrote under the real HOME ($HOME):" >&2
  echo "$written" >&2
  exit 1
fi

# The unit tests of the code that takes hostile input (pure libraries, job specs, the management
# endpoint, the fuzz budget, the drives: map files, Modbus frames, plugins; FMU archives and their
# descriptions; component plugins; the console's Prometheus text and live feed) once more under
# AddressSanitizer and UndefinedBehaviorSanitizer.
sanitized=(netsim_tests plant_tests control_tests sim_tests management_tests hostile_input_fuzz_tests drive_tests
  modbus_drive_tests plugin_drive_tests fmu_plant_tests component_plugin_tests console_tests)
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DNETMC_SANITIZE=ON \
  -DNETMC_WERROR=ON -DNETMC_BUILD_BENCHMARKS=OFF
cmake --build build-sanitize --parallel "$(nproc)" --target "${sanitized[@]}"
pattern=$(IFS='|'; echo "${sanitized[*]}")
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure --parallel "$(nproc)" --timeout 600 -R "^(${pattern})\."
