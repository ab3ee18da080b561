# Sourced by the build scripts: compile through ccache when it is installed (scripts/setup.sh
# installs it), so that the build directories of one checkout (build/, build-asan/, the
# thread-sanitizer and packaging builds) and later runs reuse each other's objects.
# Paths are taken relative to the checkout, so two build folders of it share their hits.
ccache_args=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
  export CCACHE_DIR=${CCACHE_DIR:-$HOME/.cache/ccache}
  ccache_args=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
