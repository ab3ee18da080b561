#!/usr/bin/env bash
# Held-out accuracy and error-bar coverage of every method on the bundled data, written to
# docs/accuracy.md (machine, date and commit in its header). Builds first if needed.
# Usage: scripts/accuracy.sh [--threads N]   (about 15 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
threads=0
if [[ ${1:-} == --threads ]]; then threads=$2; fi
[[ -x build/app/alloycolor && -d build/python/alloycolor ]] || scripts/setup.sh
# Debian's interpreter, which the Python package is built for: the methods come from its
# registry (alloycolor.methods()).
PYTHONPATH=build/python exec /usr/bin/python3 scripts/accuracy_table.py \
  --program build/app/alloycolor --threads "$threads" --out docs/accuracy.md
