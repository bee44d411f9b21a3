"""Every CoCo code has a model that passes and a model that fails at the expected position.

The cases are gathered in :mod:`tests.cocos.cases`; each is written to a fresh temporary
model-path root and checked in-process with :func:`workbench.check.check`.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from cocos.cases import CASES
from cocos.models import Case, materialize
from lightrocks.workbench.check import all_cocos, check
from lightrocks.workbench.diagnostics import Diagnostic

LOADER_CODES = {"LR0001", "LR0002", "LR0003", "LR0004", "LR0102", "LR0104"}


def _run(root: Path, case: Case, files: dict[str, str | bytes]) -> tuple[list[Diagnostic], tuple]:
    marked = materialize(root, files)
    paths = [root / p for p in case.paths] or [root]
    return check(paths).diagnostics.items, marked


def _where(diagnostic: Diagnostic, root: Path) -> tuple[str, int, int]:
    file = Path(diagnostic.file)
    if not file.is_absolute():
        file = Path.cwd() / file
    return (
        file.resolve().relative_to(root.resolve()).as_posix(),
        diagnostic.line,
        diagnostic.column,
    )


def test_every_code_has_a_case() -> None:
    codes = {c.code for c in all_cocos()} | LOADER_CODES
    assert codes == {case.code for case in CASES}


def test_case_ids_are_unique() -> None:
    ids = [case.id for case in CASES]
    assert len(ids) == len(set(ids))


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_passes(case: Case, tmp_path: Path) -> None:
    findings, _ = _run(tmp_path, case, {**case.base, **case.ok})
    assert [str(d) for d in findings] == []


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_fails(case: Case, tmp_path: Path) -> None:
    findings, marked = _run(tmp_path, case, {**case.base, **case.bad})
    expected = case.at or marked
    assert expected is not None, "a failing model needs a @@ marker or an explicit position"
    shown = [str(d) for d in findings]
    assert {d.code for d in findings} <= {case.code, *case.also}, shown
    mine = [d for d in findings if d.code == case.code]
    assert len(mine) == 1, shown
    finding = mine[0]
    assert _where(finding, tmp_path) == expected, shown
    assert case.message in finding.message
    assert case.hint in finding.hint
    assert finding.severity.value == ("warning" if case.code in WARNINGS else "error")


WARNINGS = {c.code for c in all_cocos() if c.severity.value == "warning"}


DOC = Path(__file__).resolve().parents[2] / "docs" / "cocos.md"


def test_every_code_is_documented() -> None:
    text = DOC.read_text(encoding="utf-8")
    for case in CASES:
        assert f"\n## {case.code}\n" in text, case.code
        assert case.message in text, case.id
