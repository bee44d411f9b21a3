"""Helpers of the generator tests: run a generator on example models in-process, and
golden-file comparison. A module of its own, not the conftest, so that a test folder's
conftest of the same name elsewhere never shadows it.

Golden files live in ``tests/generators/golden``; after an intended change of the output,
regenerate them with ``LIGHTROCKS_UPDATE_GOLDEN=1 .venv/bin/python -m pytest tests/generators``
and review the diff.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from lightrocks.workbench.check import check
from lightrocks.workbench.generators import GenerationRequest, load_generator

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
GOLDEN = Path(__file__).parent / "golden"
SCREW_TASK = EXAMPLES / "screwing" / "tasks" / "ScrewTask.lr"
RAIL_TASK = EXAMPLES / "din_rail" / "tasks" / "AssembleRail.lr"
SCREW_IN = EXAMPLES / "screwing" / "skills" / "ScrewIn.lr"


def generate(
    target: str,
    models: list[Path],
    options: dict[str, str] | None = None,
    templates=None,
    search: list[Path] | None = None,
) -> dict[str, str]:
    context = check(models, search or [EXAMPLES])
    assert not context.diagnostics.has_errors, context.diagnostics.items
    request = GenerationRequest(context, [m.resolve() for m in models], options or {}, templates)
    return load_generator(target).generate(request)


def assert_golden(name: str, text: str) -> None:
    golden = GOLDEN / name
    if os.environ.get("LIGHTROCKS_UPDATE_GOLDEN") == "1":
        golden.write_text(text, encoding="utf-8", newline="\n")
    if not golden.exists():
        pytest.fail(f"no golden file {golden}; run with LIGHTROCKS_UPDATE_GOLDEN=1")
    assert text == golden.read_text(encoding="utf-8"), f"{name} differs from its golden file"
