#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (GoogleTest through ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh chromium clang-format  # chromium: pages opened by the tests; clang-format: .ci/run
ctest --test-dir build --output-on-failure -j"$(nproc)"
