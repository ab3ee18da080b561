#!/usr/bin/env bash
# ThreadSanitizer over the library used from several threads at once: fits, colours and
# matches together (tests/concurrency_test.cc; the Python package releases the GIL around
# each, and validate and auto's folds run on threads). Its own build in build-tsan/
# (RelWithDebInfo, -fsanitize=thread), of that test's targets alone (core, model, color,
# fit and the test), compiled through ccache (scripts/ccache.sh) so that a later run reuses
# them. Any report fails the run (halt_on_error). .ci/run calls this after scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
source scripts/ccache.sh
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${ccache_args[@]}" \
  -DCMAKE_CXX_FLAGS="-fsanitize=thread -fno-omit-frame-pointer" \
  -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread \
  -DALLOYCOLOR_BUILD_BENCH=OFF -DALLOYCOLOR_BUILD_PYTHON=OFF >/dev/null
cmake --build build-tsan -j"$(nproc)" --target concurrency_test
built=$SECONDS
TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1} \
  build-tsan/tests/concurrency_test
echo "tsan: build $((built - start)) s, test $((SECONDS - built)) s"
