#!/usr/bin/env bash
# Held-out accuracy and error-bar coverage of every method on the bundled data, written to
# docs/accuracy.md (machine, date and commit in its header). Builds first if needed.
# Usage: scripts/accuracy.sh [--threads N]   (about 15 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
threads=0
if [[ ${1:-} == --threads ]]; then threads=$2; fi
[[ -x build/app/alloycolor ]] || scripts/setup.sh
exec python3 scripts/accuracy_table.py --program build/app/alloycolor --threads "$threads" \
  --out docs/accuracy.md
