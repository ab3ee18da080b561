#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (GoogleTest through ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh chromium  # chromium: the report is rendered in a real browser by the tests
ctest --test-dir build --output-on-failure -j"$(nproc)"
