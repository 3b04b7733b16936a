"""Shared fixtures of the Python module's tests: where the sources and the CLI binary are.

ctest sets LAGRANGE_SOURCE_DIR, LAGRANGE_BINARY and PYTHONPATH (tests/python/CMakeLists.txt);
run by hand from the repository root: PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python
"""

import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(
    os.environ.get("LAGRANGE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2])
)
BINARY = pathlib.Path(os.environ.get("LAGRANGE_BINARY", SOURCE_DIR / "build" / "lagrange"))


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR


@pytest.fixture(scope="session")
def examples_dir():
    return SOURCE_DIR / "examples"


@pytest.fixture(scope="session")
def cli():
    if not BINARY.exists():
        pytest.fail(f"the lagrange binary is not built: {BINARY}")
    return BINARY
