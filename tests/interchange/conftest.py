"""Plain charts checked, generated to Python (the LightRocks runtime) and to SCXML."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

from lightrocks.generators.scxml.writer import Document
from lightrocks.workbench import report
from lightrocks.workbench.check import check

from .pairs import generated

_counter = itertools.count()


@pytest.fixture
def pair(tmp_path: Path):
    """``pair(name, text)`` -> (class, SCXML document) of the plain chart ``d.<name>``."""

    def make(name: str, text: str) -> tuple[type, Document]:
        root = tmp_path / f"models{next(_counter)}"
        (root / "d").mkdir(parents=True)
        file = root / "d" / f"{name}.lr"
        file.write_text(text, encoding="utf-8")
        context = check([root])
        assert not context.diagnostics.has_errors, report.text(context.diagnostics.items)
        return generated(context, file, f"d.{name}", tmp_path / "cache")

    return make
