#!/usr/bin/env bash
# auto and the error bars measured on fresh scatter draws of the bundled series (data that
# no step of the project was tuned on), written to docs/draws.md. Builds first if needed.
# Usage: scripts/draws.sh [--seed N] [--sets N] [--subsets N] [--keep DIR] [--threads N]
#        (the defaults: about 5 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x build/app/alloycolor && -d build/python/alloycolor ]] || scripts/setup.sh
# Debian's interpreter, which the Python package is built for (python3-numpy beside it).
PYTHONPATH=build/python exec /usr/bin/python3 scripts/draws_table.py \
  --program build/app/alloycolor --out docs/draws.md "$@"
