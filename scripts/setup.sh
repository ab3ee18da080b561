#!/usr/bin/env bash
# Installs what alloycolor needs from Debian's packages (only what is missing) and builds
# it into build/. Used by scripts/main.sh and scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake ninja-build pkg-config libceres-dev libeigen3-dev
          nlohmann-json3-dev libyaml-cpp-dev libpng-dev libgtest-dev libgmock-dev
          libbenchmark-dev libcli11-dev libxml2-utils ccache
          pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest
          nodejs)  # nodejs: the explorer page's script tests (tests/js)
packages+=("$@")  # what the caller needs besides (scripts/test.sh: the test tools)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  # Another package manager holding the lock (an unattended upgrade, a second terminal):
  # wait for it, up to ten minutes, instead of failing.
  apt_waiting() {
    local log
    log=$(mktemp)
    for _ in $(seq 120); do
      if "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive "$@" 2>"$log"; then
        rm -f "$log"
        return 0
      fi
      if ! grep -qi "lock" "$log"; then
        cat "$log" >&2
        rm -f "$log"
        return 1
      fi
      echo "setup: another package manager holds the lock; waiting (up to 10 minutes)" >&2
      sleep 5
    done
    cat "$log" >&2
    rm -f "$log"
    return 1
  }
  apt_waiting apt-get update -q
  apt_waiting apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# ALLOYCOLOR_TARGETS: what to build (default: everything, the tests and benchmarks too).
read -r -a targets <<<"${ALLOYCOLOR_TARGETS:-all}"
source scripts/ccache.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${ccache_args[@]}" >/dev/null
if [[ ! -x build/app/alloycolor ]]; then
  echo "setup: first build of ${targets[*]} in build/ on $(nproc) cores: everything took about" \
       "15 minutes on 2 cores, the program alone about half of that" >&2
fi
cmake --build build -j"$(nproc)" --target "${targets[@]}"
