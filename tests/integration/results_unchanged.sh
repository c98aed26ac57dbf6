#!/usr/bin/env bash
# Every preset, and spec files written by netmc 0.1 (typed gains messages), give the JSON results
# netmc 0.1.0 gave, byte for byte: tests/data/netmc-0.1/results.sha256 holds its digests.
# Usage: results_unchanged.sh BUILD_DIR
source "$(dirname "$0")/lib.sh" "$@"
data=$(cd "$(dirname "$0")/../data/netmc-0.1" && pwd)

presets=$("$netmc" sim --list-presets | awk '{print $1}')
listed=$(awk '$2 == "preset" {print $3}' "$data/results.sha256" | sort)
[[ "$(sort <<<"$presets")" == "$listed" ]] ||
  { echo "FAIL: the presets are not those recorded:"; diff <(sort <<<"$presets") <(echo "$listed") || true; exit 1; }

checked=0
while read -r digest kind name; do
  if [[ $kind == preset ]]; then
    "$netmc" sim -q --preset "$name" --json "$tmp/$name.json" >/dev/null
  else
    "$netmc" sim -q --spec "$data/$name" --json "$tmp/$name.json" >/dev/null
  fi
  actual=$(sha256sum <"$tmp/$name.json" | cut -d' ' -f1)
  [[ $actual == "$digest" ]] || { echo "FAIL: $kind $name gives other results than netmc 0.1.0"; exit 1; }
  checked=$((checked + 1))
done <"$data/results.sha256"
echo "$checked results (every preset, 3 specs of netmc 0.1) byte-identical to netmc 0.1.0's"
