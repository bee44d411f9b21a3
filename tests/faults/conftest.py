"""Fault injection: models and adapters that fail on purpose, each run under a deadline
(:mod:`.fault_runs`); ``build`` generates a model's class within it."""

from __future__ import annotations

import itertools
from collections.abc import Callable
from pathlib import Path

import pytest

from lightrocks.app.loading import component_class, generated_package
from lightrocks.workbench import report
from lightrocks.workbench.check import check

from .fault_runs import within, write_models

_counter = itertools.count()


@pytest.fixture
def build(tmp_path: Path) -> Callable[..., type]:
    """``build({"Name": text, …}, "Name")`` -> the generated class of ``t.Name``."""

    def make(charts: dict[str, str], name: str) -> type:
        root = write_models(tmp_path / f"models{next(_counter)}", charts)
        context = check([root])
        assert not context.diagnostics.has_errors, report.text(context.diagnostics.items)
        files = sorted((root / "t").glob("*.lr"))
        package = within(lambda: generated_package(context, files, tmp_path / "cache"))
        return component_class(package, f"t.{name}")

    return make
