#!/usr/bin/env bash
# The lab deployment in containers, on this machine: a Debian 12 base made with debootstrap, the
# runtime image built from the project's .deb (docker/Dockerfile.runtime: a clean Debian 12 plus
# `apt-get install ./netmc_*.deb`), then docker/compose.yaml brought up with podman-compose
# (server, two axis nodes on a user-defined bridge, DDS discovering by multicast on it): `netmc
# nodes` and a lockstep job from the compose file's client service, whose JSON equals `netmc sim`'s
# on the host byte for byte; `netmc nodes` and the console's /metrics from the host through the
# published ports; the monitoring profile's Prometheus (Debian's package) scrapes the server;
# `docker-compose config` accepts both compose files. Everything it made goes: containers, network, images, and
# the container storage, which is its own (CONTAINERS_CONF and CONTAINERS_STORAGE_CONF point
# into its scratch directory: the machine's podman settings are not touched).
# Skips (77) with the reason where containers cannot run: not root, podman, podman-compose or
# debootstrap missing, or no Debian archive to bootstrap from.
# Usage: containers.sh BUILD_DIR
set -euo pipefail
trap 'echo "$0: failed at line $LINENO (exit $?)"' ERR
build=$(cd "$1" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
skip() { echo "skipped: $*"; exit 77; }
[ "$(id -u)" -eq 0 ] || skip "needs root (podman with its own storage, debootstrap)"
for tool in podman podman-compose debootstrap docker-compose cpack curl promtool; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (scripts/install-deps.sh installs it)"
done

tmp=$(mktemp -d /var/tmp/netmc-containers.XXXXXX)
project=netmc$$
started=$(date +%s)
cleanup() {
  local rc=$?
  if [ -f "$tmp/containers.conf" ]; then
    podman-compose -p "$project" -f "$source_dir/docker/compose.yaml" down >/dev/null 2>&1 || true
    podman network rm -f "${project}_lab" >/dev/null 2>&1 || true
    left=$(podman ps -a --format '{{.Names}}' 2>/dev/null || true)
    if [ -n "$left" ]; then
      echo "cleanup: containers left after compose down: $left" >&2
      podman rm -f $left >/dev/null 2>&1 || true
      rc=1
    fi
    # Its own images and layers (not `podman system reset`: that would remove the machine's
    # podman networks too).
    podman rmi -a -f >/dev/null 2>&1 || true
    if pgrep -f "$tmp/storage" >/dev/null; then
      echo "cleanup: container processes of this test still running:" >&2
      pgrep -af "$tmp/storage" >&2
      pkill -KILL -f "$tmp/storage" || true
      rc=1
    fi
  fi
  rm -rf "$tmp"
  exit "$rc"
}
trap cleanup EXIT

# Settings of these machines (runc, cgroupfs, lowered ulimits), for this test only.
cat >"$tmp/containers.conf" <<'CONF'
[containers]
default_ulimits = ["nofile=1024:1024", "nproc=1024:1024"]
[engine]
runtime = "runc"
cgroup_manager = "cgroupfs"
events_logger = "file"
CONF
cat >"$tmp/storage.conf" <<CONF
[storage]
driver = "overlay"
graphroot = "$tmp/storage"
runroot = "$tmp/run"
CONF
export CONTAINERS_CONF=$tmp/containers.conf CONTAINERS_STORAGE_CONF=$tmp/storage.conf

# The compose files are valid Compose (docker-compose 1.29 reads them; it needs no engine for this).
(cd "$source_dir/docker" && docker-compose -f compose.yaml config -q &&
  NETMC_INTERFACE=lo NETMC_NODE=n NETMC_AXES=x docker-compose -f compose.lab-host.yaml config -q)
echo "docker-compose config: compose.yaml and compose.lab-host.yaml accepted"

# A Debian 12 base from the archive this machine's apt uses.
mirror=$(sed -n 's/^URIs: *\(http[^ ]*debian\)$/\1/p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -n 1)
mirror=${mirror:-http://deb.debian.org/debian}
debootstrap --variant=minbase bookworm "$tmp/rootfs" "$mirror" >"$tmp/debootstrap.log" 2>&1 ||
  skip "debootstrap from $mirror failed: $(tail -n 1 "$tmp/debootstrap.log")"
tar -C "$tmp/rootfs" -c . | podman import - localhost/netmc-test-base:12 >"$tmp/import.log" 2>&1
rm -rf "$tmp/rootfs"
podman run --rm localhost/netmc-test-base:12 true 2>"$tmp/run.err" ||
  skip "podman cannot run a container here: $(tail -n 1 "$tmp/run.err")"
echo "base image: debootstrap bookworm minbase from $mirror, $(( $(date +%s) - started )) s"

# The runtime image from the project's package.
mkdir "$tmp/context"
cpack --config "$build/CPackConfig.cmake" -B "$tmp/package" >"$tmp/cpack.log" 2>&1
cp "$tmp/package"/netmc_*.deb "$source_dir/docker/entrypoint.sh" "$tmp/context/"
podman build --network host --build-arg BASE=localhost/netmc-test-base:12 -f "$source_dir/docker/Dockerfile.runtime" \
  -t localhost/netmc:test "$tmp/context" >"$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; exit 1; }
base_mb=$(( $(podman image inspect --format '{{.Size}}' localhost/netmc-test-base:12) / 1000000 ))
image_mb=$(( $(podman image inspect --format '{{.Size}}' localhost/netmc:test) / 1000000 ))
echo "runtime image: $image_mb MB ($base_mb MB of it the Debian 12 base)"
podman run --rm localhost/netmc:test netmc --version
podman run --rm localhost/netmc:test sim --quiet --controller adrc --iterations 1 | grep -q "^adrc " ||
  { echo "FAIL: netmc sim does not run in the image"; exit 1; }
echo "the .deb installed on a clean Debian 12 runs netmc sim"
# python3-netmc beside netmc on the same clean base: it installs (Debian's numpy and pandas come
# with it) and imports, and its study is the CLI's.
if ls "$tmp/package"/python3-netmc_*.deb >/dev/null 2>&1; then
  podman run --rm --network host -v "$tmp/package:/packages:ro" localhost/netmc-test-base:12 bash -c '
    apt-get update >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      /packages/netmc_*.deb /packages/python3-netmc_*.deb >/dev/null &&
    python3 -c "import netmc; s = netmc.sim(controller=\"adrc\", iterations=1); print(netmc.__version__, s.labels, len(s.trace(\"adrc\")[\"time_s\"]))" &&
    netmc sim -q --controller adrc --iterations 1 --json /tmp/cli.json >/dev/null &&
    python3 -c "import netmc; assert netmc.sim(controller=\"adrc\", iterations=1).to_json() == open(\"/tmp/cli.json\").read()"' \
    >"$tmp/python.log" 2>&1 || { echo "FAIL: python3-netmc did not install or import on a clean Debian 12"; cat "$tmp/python.log"; exit 1; }
  echo "python3-netmc installed beside netmc on a clean Debian 12: $(tail -n 1 "$tmp/python.log"); netmc.sim() JSON = netmc sim --json"
fi

# The lab: server and two axis nodes, then the client service.
port=$(( 17300 + RANDOM % 1000 ))
console_port=$(( port + 1000 ))
prometheus_port=$(( port + 2000 ))
export NETMC_IMAGE=localhost/netmc:test NETMC_PUBLISH=127.0.0.1:$port NETMC_DOMAIN=$(( RANDOM % 200 ))
export NETMC_CONSOLE_PUBLISH=127.0.0.1:$console_port NETMC_PROMETHEUS_PUBLISH=127.0.0.1:$prometheus_port
export NETMC_PROMETHEUS_IMAGE=localhost/netmc-prometheus:test
compose() { podman-compose -p "$project" -f "$source_dir/docker/compose.yaml" "$@"; }
compose up -d server axis-x axis-y >"$tmp/up.log" 2>&1 || { cat "$tmp/up.log"; exit 1; }
up=$(date +%s)
for _ in $(seq 30); do
  compose run --rm -T client netmc nodes >"$tmp/nodes.txt" 2>&1 || true
  [ "$(grep -c '^axis-[xy] .*idle' "$tmp/nodes.txt" || true)" -eq 2 ] && break
  sleep 1
done
grep '^node\|^axis-' "$tmp/nodes.txt"
[ "$(grep -c '^axis-[xy] .*idle' "$tmp/nodes.txt" || true)" -eq 2 ] ||
  { echo "FAIL: the server did not discover both axis nodes"; cat "$tmp/nodes.txt"; podman logs "${project}_server_1"; exit 1; }
"$build/client/netmc" nodes --server "127.0.0.1:$port" | grep -q '^axis-x ' ||
  { echo "FAIL: the published management port does not answer from the host"; exit 1; }
echo "netmc nodes from the client service and from the host (127.0.0.1:$port): axis-x and axis-y"
curl -s -f "http://127.0.0.1:$console_port/metrics" >"$tmp/metrics.txt" ||
  { echo "FAIL: the published console port does not answer from the host"; exit 1; }
grep -q '^netmc_nodes_up 2$' "$tmp/metrics.txt" || { echo "FAIL: /metrics does not show both nodes"; cat "$tmp/metrics.txt"; exit 1; }
promtool check metrics <"$tmp/metrics.txt"
echo "console from the host (127.0.0.1:$console_port): /metrics shows netmc_nodes_up 2, promtool check metrics: no complaint"
# The monitoring profile: Prometheus from Debian's package scraping the server in the lab network.
promtool check config "$source_dir/docker/prometheus.yml" >/dev/null
podman build --network host --build-arg BASE=localhost/netmc-test-base:12 -f "$source_dir/docker/Dockerfile.prometheus" \
  -t localhost/netmc-prometheus:test "$source_dir/docker" >"$tmp/prometheus-build.log" 2>&1 ||
  { cat "$tmp/prometheus-build.log"; exit 1; }
compose up -d prometheus >"$tmp/prometheus-up.log" 2>&1 || { cat "$tmp/prometheus-up.log"; exit 1; }
scraped=""
for _ in $(seq 60); do
  scraped=$(curl -s "http://127.0.0.1:$prometheus_port/api/v1/query?query=netmc_nodes_up" |
    python3 -c 'import json,sys; r=json.load(sys.stdin)["data"]["result"]; print(r[0]["value"][1] if r else "")' 2>/dev/null || true)
  [ "$scraped" = 2 ] && break
  sleep 1
done
[ "$scraped" = 2 ] || { echo "FAIL: Prometheus did not scrape netmc_nodes_up 2 from the server"; podman logs "${project}_prometheus_1" | tail -20; exit 1; }
echo "monitoring profile: Prometheus (Debian's package) scraped netmc_nodes_up = 2 from server:7380"
study=(--controller adrc+ilccc --iterations 2)
compose run --rm -T client netmc run --quiet "${study[@]}" --json - >"$tmp/run.out" 2>"$tmp/run.err" ||
  { cat "$tmp/run.out" "$tmp/run.err"; exit 1; }
sed -n '/^{$/,/^}$/p' "$tmp/run.out" >"$tmp/run.json"  # podman-compose says things on stdout too
"$build/client/netmc" sim --quiet "${study[@]}" --json "$tmp/sim.json" >/dev/null
if ! cmp -s "$tmp/sim.json" "$tmp/run.json"; then
  echo "FAIL: the job in containers differs from netmc sim:"
  diff "$tmp/sim.json" "$tmp/run.json" | head -20
  exit 1
fi
echo "lockstep job (adrc+ilccc, 2 iterations) in containers equals netmc sim: identical JSON ($(wc -c <"$tmp/run.json") bytes)"
compose down >"$tmp/down.log" 2>&1
echo "compose up to down: $(( $(date +%s) - up )) s; whole test: $(( $(date +%s) - started )) s"
