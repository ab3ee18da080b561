#!/usr/bin/env bash
# The installed copies proven, not the build tree (.ci/run calls this after scripts/test.sh):
#  1. the wheel from scripts/package.sh installed into a fresh virtual environment that sees
#     Debian's numpy, and the Python tests (tests/python) run on it from outside the checkout;
#  2. the .deb installed with dpkg (system-wide: it needs root or sudo), the program and the
#     Python package used from /tmp and /, then removed, leaving none of its files;
#  3. the add-on's zip checked against Blender's rules for add-ons and extensions, then
#     installed into Blender (headless) with the installed program, and its material rendered
#     against `alloycolor color` (tests/blender/blender_test.py); a visible skip without
#     Blender.
# A Debian package alloycolor installed before is removed first (an earlier run cut short).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
start=$SECONDS
sudo_cmd=()
[[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
installed() { dpkg-query -W -f='${Status}' alloycolor 2>/dev/null | grep -q "ok installed"; }
if installed; then
  echo "installed_check: removing the alloycolor package left installed before" >&2
  "${sudo_cmd[@]}" dpkg -r alloycolor >/dev/null
fi

bash scripts/package.sh
packaged=$SECONDS
python=$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' build/CMakeCache.txt)
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:[A-Z]*=//p' build/CMakeCache.txt)
wheel=$(ls "$root"/dist/alloycolor-"$version"-*.whl)
deb=$(ls "$root"/dist/alloycolor_"$version"_*.deb)
zip=$root/dist/alloycolor_material-$version.zip
tmp=$(mktemp -d /tmp/alloycolor-installed.XXXXXX)
cleanup() {
  if installed; then "${sudo_cmd[@]}" dpkg -r alloycolor >/dev/null; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

# Everything from here on runs outside the checkout, as a user's would.
cd "$tmp"

# 1. The wheel: a fresh venv, nothing from a package index (--no-index).
"$python" -m venv --system-site-packages "$tmp/venv"
venv_python=$tmp/venv/bin/python
"$venv_python" -m pip install --no-index --quiet "$wheel"
"$venv_python" - "$tmp/venv" <<'EOF'
import sys, alloycolor as ac
assert ac.__file__.startswith(sys.argv[1]), "alloycolor imported from " + ac.__file__
assert ac.data_root().startswith(sys.argv[1]), "data from " + ac.data_root()
print("installed_check: the wheel's alloycolor %s in %s, its data in %s"
      % (ac.__version__, ac.__file__, ac.data_root()))
EOF
ALLOYCOLOR_BINARY=$root/build/app/alloycolor PYTHONDONTWRITEBYTECODE=1 \
  "$venv_python" -m pytest -q -p no:cacheprovider "$root/tests/python"
wheeled=$SECONDS

# 2. The .deb: its declared dependencies, then installed, used from / and /tmp, removed.
dpkg-deb --field "$deb" Package Version Depends
"${sudo_cmd[@]}" dpkg -i "$deb" >/dev/null
(cd / && /usr/bin/alloycolor color --data Au-Ag --x 18k)
/usr/bin/alloycolor fit --data Au-Ag --out "$tmp/auag.model.json" --quiet
/usr/bin/alloycolor color --model "$tmp/auag.model.json" --x 0.75 --json >"$tmp/installed.json"
(cd "$root" && build/app/alloycolor color --model "$tmp/auag.model.json" --x 0.75 --json) \
  >"$tmp/built.json"
cmp "$tmp/installed.json" "$tmp/built.json"
/usr/bin/python3 -I - <<'EOF'
import alloycolor as ac
assert ac.__file__.startswith("/usr/lib/python3/dist-packages/"), ac.__file__
m = ac.fit(ac.Dataset("Au-Ag"))
print("installed_check: the .deb's alloycolor from %s, data %s, 75 %% Au-Ag: Lab %s"
      % (ac.__file__, ac.data_root(), ac.color(m, x=0.75)["lab"]))
EOF
debbed=$SECONDS

# 3. The add-on: its zip, then Blender with the .deb's program.
"$python" "$root/tests/blender/addon_zip_check.py" "$zip" "$version"
blender_status=0
"$python" "$root/tests/blender/blender_test.py" --program /usr/bin/alloycolor --zip "$zip" \
  --version "$version" || blender_status=$?
if ((blender_status == 77)); then
  echo "installed_check: SKIPPED the add-on in Blender: no Blender (Debian package blender)"
elif ((blender_status != 0)); then
  exit "$blender_status"
fi
blended=$SECONDS

files=$(dpkg -L alloycolor | while read -r f; do if [[ -f $f ]]; then echo "$f"; fi; done)
"${sudo_cmd[@]}" dpkg -r alloycolor >/dev/null
left=$(for f in $files /usr/lib/python3/dist-packages/alloycolor /usr/share/alloycolor \
                /usr/include/alloycolor /usr/lib/cmake/alloycolor; do
         if [[ -e $f ]]; then echo "$f"; fi; done)
if [[ -n $left ]]; then
  echo "installed_check: dpkg -r alloycolor left: $left" >&2
  exit 1
fi
echo "installed_check: dpkg -r alloycolor removed all $(wc -w <<<"$files") files"
echo "installed_check: packaging $((packaged - start)) s, wheel $((wheeled - packaged)) s," \
     ".deb $((debbed - wheeled)) s, add-on $((blended - debbed)) s, all $((SECONDS - start)) s"
