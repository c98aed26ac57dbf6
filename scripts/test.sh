#!/usr/bin/env bash
# All tests: install dependencies, build with warnings as errors, run every ctest label.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# The test build carries the test suite's own controller (tests/components).
bash scripts/build.sh -DNETMC_WERROR=ON -DNETMC_TEST_COMPONENTS=ON

# The unit tests of the code that takes hostile input (pure libraries, job specs, the management
# endpoint, the fuzz budget, the drives: map files, Modbus frames, plugins; FMU archives and their
# descriptions; component plugins; the console's Prometheus text and live feed) run once more
# under AddressSanitizer and UndefinedBehaviorSanitizer, from a build of their own.
sanitized=(netsim_tests plant_tests control_tests sim_tests management_tests hostile_input_fuzz_tests drive_tests
  modbus_drive_tests plugin_drive_tests fmu_plant_tests component_plugin_tests console_tests)
mkdir -p build-sanitize
log=build-sanitize/netmc-build.log
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DNETMC_SANITIZE=ON \
  -DNETMC_WERROR=ON -DNETMC_BUILD_BENCHMARKS=OFF >"$log" 2>&1 || { cat "$log" >&2; exit 1; }
# Tests run with a private HOME and XDG_STATE_HOME (build/test-home, set by CMakeLists.txt): the
# user's own may gain no file while they run.
marker=$(mktemp)
status=0
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600 || status=$?
if [ "$status" -ne 0 ]; then
  # The failures once more, last: a long log's reader (or a CI page that keeps only its end) sees
  # why each test failed without scrolling back through the suite.
  bash scripts/failed-tests-summary.sh build >&2 || true
  exit "$status"
fi
written=$(find "$HOME/.local" "$HOME/.config" -type f -newer "$marker" 2>/dev/null | head -20 || true)
rm -f "$marker"
if [ -n "$written" ]; then
  echo "FAIL: the tests wrote under the real HOME ($HOME):" >&2
  echo "$written" >&2
  exit 1
fi

# After the suite, not beside it: a build on both cores, even under SCHED_IDLE, delayed the
# realtime tests' loops by tens of ms (three fresh-clone runs, three different realtime failures).
cmake --build build-sanitize --parallel "$(nproc)" --target "${sanitized[@]}" >>"$log" 2>&1 ||
  { tail -n 60 "$log" >&2; echo "FAIL: the sanitized build failed" >&2; exit 1; }
tail -n 1 "$log"
pattern=$(IFS='|'; echo "${sanitized[*]}")
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure --parallel "$(nproc)" --timeout 600 -R "^(${pattern})\."
