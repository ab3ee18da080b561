"""The Python package built by the project's own CMake build (pip, python -m build).

setuptools is the build back end (pyproject.toml); its build_ext step configures CMake in
build-pkg/ (tests and benchmarks off, ALLOYCOLOR_PYTHON_BUNDLE_DATA on), builds the one
target _alloycolor and copies the package CMake assembled, python/alloycolor with its
extension module and the bundled data in alloycolor/data, into the wheel. The version is
the CMake project's (CMakeLists.txt). Offline, as on a machine without a package index:

    pip install --no-build-isolation .         # Debian 12: python3-setuptools, python3-wheel
    python3 -m build --wheel --no-isolation    # Debian 12: python3-build

CMAKE_ARGS (space separated) is added to the CMake configuration, as scikit-build reads it:
scripts/package.sh passes ccache there, CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs.
"""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
# One level below the checkout, as build/ is: with CCACHE_BASEDIR at the checkout
# (scripts/ccache.sh) the two compile with the same relative paths and share cache hits.
BUILD_DIR = ROOT / "build-pkg"


def project_version():
    """The VERSION of project(alloycolor ...) in CMakeLists.txt: the one place it is set."""
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    found = re.search(r"project\(\s*alloycolor\s+VERSION\s+([0-9][0-9.]*)", text)
    if not found:
        sys.exit("setup.py: CMakeLists.txt: no project(alloycolor VERSION x.y.z)")
    return found.group(1)


class CMakeBuild(build_ext):
    """Builds the extension with CMake and copies the whole package beside it."""

    def build_extension(self, ext):
        if self.inplace or getattr(self, "editable_mode", False):
            sys.exit("setup.py: no editable install (pip install -e): the package is assembled "
                     "by CMake; use PYTHONPATH=build/python after building (docs/python.md)")
        if shutil.which("cmake") is None:
            sys.exit("setup.py: cmake not found (Debian: apt-get install cmake ninja-build, "
                     "and the libraries scripts/setup.sh lists)")
        configure = ["cmake", "-S", str(ROOT), "-B", str(BUILD_DIR),
                     "-DCMAKE_BUILD_TYPE=Release",
                     "-DALLOYCOLOR_BUILD_TESTS=OFF", "-DALLOYCOLOR_BUILD_BENCH=OFF",
                     "-DALLOYCOLOR_BUILD_PYTHON=ON", "-DALLOYCOLOR_PYTHON_BUNDLE_DATA=ON",
                     "-DPython_EXECUTABLE=" + sys.executable]
        if shutil.which("ninja") and not (BUILD_DIR / "CMakeCache.txt").exists():
            configure += ["-G", "Ninja"]
        configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(BUILD_DIR), "--target", "_alloycolor",
                        "-j", jobs], check=True)
        package = BUILD_DIR / "python" / "alloycolor"
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).parent
        if target.exists():
            shutil.rmtree(target)
        shutil.copytree(package, target, ignore=shutil.ignore_patterns("__pycache__"))


BUILD_DIR.mkdir(exist_ok=True)
setup(
    version=project_version(),
    # The package is what CMake assembled (CMakeBuild copies it): nothing for setuptools to
    # find in the checkout, whose C++ folders would look like packages to it.
    packages=[],
    py_modules=[],
    ext_modules=[Extension("alloycolor._alloycolor", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own folders in build-pkg/ too: build/ is the CMake build of the README.
    options={"build": {"build_base": str(BUILD_DIR / "setuptools")},
             "egg_info": {"egg_base": str(BUILD_DIR)}},
)
