#!/usr/bin/env bash
# Installs every build and test dependency from Debian 12 packages (run as root).
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: run as root (apt-get needs it)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends \
  build-essential cmake ninja-build pkg-config \
  libeigen3-dev \
  libprotobuf-dev protobuf-compiler \
  libfastrtps-dev libfastcdr-dev fastddsgen \
  libboost-dev libboost-system-dev \
  libcli11-dev libfmt-dev libspdlog-dev nlohmann-json3-dev \
  gnuplot-nox \
  iproute2 nftables util-linux fastdds-tools rt-tests openssl \
  libgtest-dev libgmock-dev libbenchmark-dev
