# Shared fixtures for the Python package's tests (run by ctest: see tests/CMakeLists.txt).
import os
import pathlib

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
DATA = REPO / "data"


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
