"""Fixtures of the generator tests (their helpers are in ``generation``)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from judges import missing
from plc import matiec_home


@pytest.fixture(scope="module")
def home() -> Path:
    """MatIEC's folder, for the tests it judges (see ``judges.missing`` where it or gcc is
    absent)."""
    found = matiec_home()
    if found is None:
        missing("MatIEC", "`make judges`, or ../shared/tools/matiec/build.sh DIR and MATIEC=DIR")
    if shutil.which("gcc") is None:
        missing("gcc", "apt-get install gcc")
    return found
