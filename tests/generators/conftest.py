"""Fixtures of the generator tests (their helpers are in ``generation``)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from plc import matiec_home


@pytest.fixture(scope="module")
def home() -> Path:
    """MatIEC's folder, for the tests it judges; they skip with the reason where it or gcc
    is absent."""
    found = matiec_home()
    if found is None:
        pytest.skip("MatIEC not found: set MATIEC=<dir> or build it in /opt/matiec")
    if shutil.which("gcc") is None:
        pytest.skip("gcc not found")
    return found
