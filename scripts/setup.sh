#!/usr/bin/env bash
# Installs what alloycolor needs from Debian's packages (only what is missing) and builds
# it into build/. Used by scripts/main.sh and scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake ninja-build pkg-config libceres-dev libeigen3-dev
          nlohmann-json3-dev libyaml-cpp-dev libpng-dev libgtest-dev libgmock-dev
          libbenchmark-dev libcli11-dev libxml2-utils
          pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest
          nodejs)  # nodejs: the explorer page's script tests (tests/js)
packages+=("$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -q
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
