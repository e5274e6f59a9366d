#!/usr/bin/env bash
# Installs what wrc needs from Debian's packages (only what is missing), then
# configures and builds into build/. Usage: tools/setup.sh [extra cmake args...]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake make pkg-config libeigen3-dev libfftw3-dev libhdf5-dev libgsl-dev
  libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev libtomlplusplus-dev
  clang-format python3 python3-numpy python3-pybind11 python3-venv python3-pip python3-setuptools pybind11-dev gnuplot-nox nettle-dev libzip-dev libxml2-utils openmpi-bin libopenmpi-dev clang libclang-rt-14-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DWRC_WERROR=OFF "$@" >/dev/null
cmake --build build -j "$(nproc)"
