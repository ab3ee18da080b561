# Shared fixtures for the Python package's tests (run by ctest: see tests/CMakeLists.txt).
import importlib.util
import os
import pathlib

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
DATA = REPO / "data"


def load_script(name):
    """scripts/<name>.py as a module."""
    spec = importlib.util.spec_from_file_location(name, REPO / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def binary():
    path = os.environ.get("ALLOYCOLOR_BINARY")
    if not path or not os.path.exists(path):
        pytest.fail("ALLOYCOLOR_BINARY must name the built alloycolor program")
    return path


@pytest.fixture(scope="session")
def au_ag():
    import alloycolor
    return alloycolor.Dataset("Au-Ag")
