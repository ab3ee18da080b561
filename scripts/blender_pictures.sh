#!/usr/bin/env bash
# docs/images/blender-rings.png: rings of 18k Au-Ag, Cu70Zn30 brass and copper with the Blender
# add-on's material (table mode), rendered by Blender (Cycles, CPU) from tables the
# program exports. Needs build/app/alloycolor and blender (Debian package blender).
set -euo pipefail
cd "$(dirname "$0")/.."
program=${ALLOYCOLOR:-build/app/alloycolor}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for system in Au-Ag Cu-Zn; do
  "$program" fit --data "$system" --method eps-linear --out "$tmp/$system.model.json" --quiet
  "$program" export --model "$tmp/$system.model.json" --format blender-table \
    --out "$tmp/$system" --quiet
done
# The panel itself cannot be drawn without a display: only the render is made here.
blender --background --factory-startup --python-exit-code 1 \
  --python scripts/blender_pictures.py -- "$PWD/docs/images/blender-rings.png" \
  "$tmp/Au-Ag.alloy-table.json" karat 18 \
  "$tmp/Cu-Zn.alloy-table.json" at_percent 70 \
  "$tmp/Cu-Zn.alloy-table.json" at_percent 100 >"$tmp/blender.log" 2>&1 ||
  { cat "$tmp/blender.log" >&2; exit 1; }
echo "wrote docs/images/blender-rings.png ($(stat -c %s docs/images/blender-rings.png) bytes)"
