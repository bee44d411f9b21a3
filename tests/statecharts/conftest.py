"""Builds plain charts from text for the differential runs."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

from lightrocks.app.loading import component_class, generated_package
from lightrocks.workbench import report
from lightrocks.workbench.check import check

_counter = itertools.count()


@pytest.fixture
def build(tmp_path: Path):
    """``build(name, text)`` -> the generated class of the plain chart ``d.<name>``."""

    def make(name: str, text: str) -> type:
        root = tmp_path / f"models{next(_counter)}"
        (root / "d").mkdir(parents=True)
        file = root / "d" / f"{name}.lr"
        file.write_text(text)
        context = check([root])
        shown = report.text(context.diagnostics.items)
        assert not context.diagnostics.has_errors, shown
        package = generated_package(context, [file], tmp_path / "cache")
        return component_class(package, f"d.{name}")

    return make
