#!/usr/bin/env bash
# docs/images/blender-rings.png: rings of 18k Au-Ag, Cu70Zn30 brass and copper with the Blender
# add-on's material (table mode), rendered by Blender (Cycles, CPU) from tables the
# program exports; docs/images/blender-panel.png: the add-on's panel, a screenshot of Blender
# drawn on a virtual display (xvfb-run). Installs what it needs (Debian's blender and xvfb)
# and builds the program (scripts/setup.sh) unless ALLOYCOLOR names a program to use.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -z ${ALLOYCOLOR:-} ]]; then
  ALLOYCOLOR_TARGETS=alloycolor scripts/setup.sh blender xvfb
fi
program=${ALLOYCOLOR:-build/app/alloycolor}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for system in Au-Ag Cu-Zn; do
  "$program" fit --data "$system" --method eps-linear --out "$tmp/$system.model.json" --quiet
  "$program" export --model "$tmp/$system.model.json" --format blender-table \
    --out "$tmp/$system" --quiet
done
blender --background --factory-startup --python-exit-code 1 \
  --python scripts/blender_pictures.py -- "$PWD/docs/images/blender-rings.png" \
  "$tmp/Au-Ag.alloy-table.json" karat 18 \
  "$tmp/Cu-Zn.alloy-table.json" at_percent 70 \
  "$tmp/Cu-Zn.alloy-table.json" at_percent 100 >"$tmp/blender.log" 2>&1 ||
  { cat "$tmp/blender.log" >&2; exit 1; }
echo "wrote docs/images/blender-rings.png ($(stat -c %s docs/images/blender-rings.png) bytes)"
# A user configuration of its own: no splash screen, nothing saved to the user's, the
# session Blender saves on quitting kept in $tmp.
mkdir -p "$tmp/config" "$tmp/scripts"
export BLENDER_USER_CONFIG=$tmp/config BLENDER_USER_SCRIPTS=$tmp/scripts
blender --background --factory-startup --python-expr \
  "import bpy; p = bpy.context.preferences; p.view.show_splash = False; \
p.filepaths.temporary_directory = '$tmp'; bpy.ops.wm.save_userpref()" \
  >"$tmp/blender.log" 2>&1 || { cat "$tmp/blender.log" >&2; exit 1; }
(cd "$tmp" && xvfb-run -a -s "-screen 0 900x1250x24" blender --python-exit-code 1 \
  --python "$OLDPWD/scripts/blender_panel.py" -- "$OLDPWD/docs/images/blender-panel.png" \
  "$tmp/Au-Ag.alloy-table.json") >"$tmp/blender.log" 2>&1 || { cat "$tmp/blender.log" >&2; exit 1; }
echo "wrote docs/images/blender-panel.png ($(stat -c %s docs/images/blender-panel.png) bytes)"
