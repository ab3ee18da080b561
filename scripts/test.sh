#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (GoogleTest through ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
# chromium: pages opened by the tests; clang-format: .ci/run; blender: the add-on's render
# test (174 packages, 766 MB, about a minute on a fast mirror); npm: three.js for the glTF
# check. NodeSource's nodejs carries its own npm (and conflicts with Debian's), so Debian's
# is installed only when there is none.
tools=(chromium clang-format blender)
command -v npm >/dev/null || tools+=(npm)
scripts/setup.sh "${tools[@]}"
# three.js for the glTF check (tests/three_gltf_test.cc) at the version tests/three's lock
# file pins, when it is not there yet: the network is used here, never by the build or tests.
three_pinned=$(node -p "require('./tests/three/package.json').dependencies.three")
three_here=$(node -p "try { require('./tests/three/node_modules/three/package.json').version }
                      catch (e) { 'none' }")
if [[ "$three_here" != "$three_pinned" ]]; then
  echo "test: npm ci in tests/three (three $three_pinned)" >&2
  (cd tests/three && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
ctest --test-dir build --output-on-failure -j"$(nproc)"
