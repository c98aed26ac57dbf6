#!/usr/bin/env bash
# The main job: install dependencies, build, run the in-process study (default: paper 001,
# Table 1). Arguments go to `netmc sim`, e.g. scripts/run.sh --preset seed001-ellipse --curve.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh >/dev/null
bash scripts/build.sh >/dev/null
exec build/client/netmc sim "$@"
