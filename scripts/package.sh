#!/usr/bin/env bash
# Writes alloycolor in the three forms its users install into dist/ (VERSION: the CMake
# project's, CMakeLists.txt):
#   alloycolor-VERSION-cpXY-cpXY-linux_ARCH.whl  the Python package, data inside (pip)
#   alloycolor_VERSION_ARCH.deb                  program, data, Python package, C++ libraries
#                                                and CMake package (dpkg -i, apt install ./)
#   alloycolor_material-VERSION.zip              the Blender add-on (3.4+; 4.2+ extension)
# Installs what is missing (scripts/setup.sh, with the packaging tools), brings build/ up to
# date for the program, the Python module and the add-on's zip, makes the .deb from build/'s
# install rules (cpack), and the wheel with python3 -m build in build-pkg/ (no isolation: no
# package index is needed; with the same flags as build/, its objects come from ccache).
# docs/install.md says how each is installed.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
ALLOYCOLOR_TARGETS=${ALLOYCOLOR_TARGETS:-alloycolor _alloycolor blender_addon} \
  scripts/setup.sh python3-build python3-venv python3-setuptools python3-wheel python3-pip \
                   dpkg-dev
cache() { sed -n "s/^$1:[A-Z]*=//p" build/CMakeCache.txt; }
version=$(cache CMAKE_PROJECT_VERSION)
python=$(cache Python_EXECUTABLE)
mkdir -p dist
rm -f dist/alloycolor-*.whl dist/alloycolor_*.deb dist/alloycolor_material-*.zip

# The add-on, as build/ zipped it.
cp build/alloycolor_material.zip "dist/alloycolor_material-$version.zip"

# The Debian package from build/'s install rules; cpack's scratch folder in build-pkg/.
cpack --config build/CPackConfig.cmake -G DEB -B build-pkg/deb >/dev/null
mv build-pkg/deb/alloycolor_"$version"_*.deb dist/
debbed=$SECONDS

# The wheel, by setup.py's CMake build in build-pkg/ through ccache (scripts/ccache.sh),
# which says how many of its compilations came from the cache.
source scripts/ccache.sh
stats=$PWD/build-pkg/ccache-stats.log
rm -f "$stats"
CCACHE_STATSLOG=$stats CMAKE_ARGS="${ccache_args[*]}" \
  "$python" -m build --wheel --no-isolation --outdir dist . >build-pkg/wheel.log 2>&1 ||
  { cat build-pkg/wheel.log >&2; exit 1; }
if [[ -s $stats ]]; then
  echo "package: the wheel's compilations from ccache:" \
       "$(CCACHE_STATSLOG=$stats ccache --show-log-stats | sed -n 's/^ *Hits: *//p' | head -1)"
fi

ls -l dist/alloycolor-"$version"-*.whl dist/alloycolor_"$version"_*.deb \
      dist/alloycolor_material-"$version".zip
echo "package: setup and .deb $((debbed - start)) s, wheel $((SECONDS - debbed)) s"
