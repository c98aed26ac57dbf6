#!/usr/bin/env bash
# All tests: install dependencies, build with warnings as errors, run every ctest label.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DNETMC_WERROR=ON
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600
