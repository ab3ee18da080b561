#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer: a separate
# build in build-asan/ (-DALLOYCOLOR_SANITIZE=ON, RelWithDebInfo, no benchmarks, no Python
# module: an uninstrumented interpreter cannot load ASan-instrumented code), then ctest.
# Every test that runs the real program runs the sanitized one. .ci/run calls this after
# scripts/test.sh (which installs the packages).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
source scripts/ccache.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DALLOYCOLOR_SANITIZE=ON \
  "${ccache_args[@]}" \
  -DALLOYCOLOR_BUILD_BENCH=OFF -DALLOYCOLOR_BUILD_PYTHON=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
built=$SECONDS
# Any report fails the test that triggered it (UBSan is built with -fno-sanitize-recover).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir build-asan --output-on-failure -j"$(nproc)"
echo "sanitize: build $((built - start)) s, tests $((SECONDS - built)) s"
