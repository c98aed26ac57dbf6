#!/usr/bin/env bash
# Installs every build and test dependency from Debian 12 packages (run as root).
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: run as root (apt-get needs it)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
# What building the programs and the .deb needs (--build-only: docker/Dockerfile's build stage).
build=(build-essential cmake ninja-build pkg-config dpkg-dev file
  libeigen3-dev
  libprotobuf-dev protobuf-compiler
  libfastrtps-dev libfastcdr-dev fastddsgen
  libboost-dev libboost-system-dev libssl-dev
  libcli11-dev libfmt-dev libspdlog-dev nlohmann-json3-dev
  libmodbus-dev libzip-dev libtinyxml2-dev libsqlite3-dev
  pybind11-dev python3-dev python3-numpy python3-pandas)
# What the tests and benchmarks use besides: gnuplot for figures, namespaces and nftables for
# test hosts, libfaketime for a wall-clock step seen by one process only, rt-tests for the
# machine's latency, openssl for DDS Security certificates, systemd for checking the units,
# podman with compose for the container test, and for the console: Debian's dygraphs (the page's
# plots), a headless browser driven by selenium, a WebSocket client and promtool (prometheus) for
# /metrics; Dask (python3-distributed) for the Python package's sweeps on a cluster, nbclient, ipykernel
# and matplotlib for its notebook (examples/notebooks), Slurm (slurm-wlm, munge) for a job array of
# sweep parts.
tests=(gnuplot-nox
  iproute2 nftables util-linux fastdds-tools rt-tests openssl systemd sqlite3 libfaketime
  podman podman-compose runc debootstrap golang-github-containernetworking-plugin-dnsname dnsmasq-base
  docker-compose uidmap
  libgtest-dev libgmock-dev libbenchmark-dev
  libjs-dygraphs chromium chromium-driver python3-selenium python3-websocket prometheus curl
  python3-distributed python3-nbclient python3-ipykernel python3-matplotlib slurm-wlm munge)
apt-get update
if [ "${1:-}" = "--build-only" ]; then
  apt-get install -y --no-install-recommends "${build[@]}"
else
  apt-get install -y --no-install-recommends "${build[@]}" "${tests[@]}"
fi
