#!/usr/bin/env bash
# How often `fit` calls an honest sample suspect: freshly drawn series with real films'
# scatter (scripts/draws_table.py's draws) fitted as a user fits them, every sample their
# fit.suspect_samples names counted, written to docs/suspects.md. Builds first if needed.
# Usage: scripts/suspects.sh [--seeds N,M] [--sets N] [--threads N]
#        (the defaults, 120 series: about 5 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x build/app/alloycolor && -d build/python/alloycolor ]] || scripts/setup.sh
# Debian's interpreter, which the Python package is built for (python3-numpy beside it).
PYTHONPATH=build/python exec /usr/bin/python3 scripts/suspects_table.py \
  --program build/app/alloycolor --out docs/suspects.md "$@"
