#!/usr/bin/env bash
# Configures and builds netmc (Release, Ninja) into ./build.
set -euo pipefail
cd "$(dirname "$0")/.."
# Test-only components are off unless asked for (the cache would keep them from a test build).
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DNETMC_TEST_COMPONENTS=OFF "$@"
cmake --build build --parallel "$(nproc)"
