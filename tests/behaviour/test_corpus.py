"""A corpus of deliberately broken copies of the models: each folder holds one changed model
file and ``expect.json``, the finding it must cause (code, file, line, column; the stage,
``check`` or ``verify``; the root it belongs to, the examples unless ``root`` names another
folder of the repository). Every case is a regression test: the finding is reported at its
cause."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from lightrocks.languages.lightrocks.behaviour.verify import verify
from lightrocks.workbench.check import check
from lightrocks.workbench.diagnostics import Diagnostic

ROOT = Path(__file__).resolve().parents[2]
CORPUS = Path(__file__).with_name("corpus")
MINIMUM_CASES, MINIMUM_KINDS = 48, 16


def _cases() -> list[Path]:
    return sorted(p for p in CORPUS.iterdir() if (p / "expect.json").is_file())


def _expect(case: Path) -> dict:
    return json.loads((case / "expect.json").read_text(encoding="utf-8"))


def _findings(case: Path) -> tuple[Path, list[Diagnostic]]:
    """The broken file and the findings on it with its text substituted, its root the model
    path (what a user runs on the file they changed)."""
    expect = _expect(case)
    root = ROOT / expect.get("root", "examples")
    file = (root / expect["file"]).resolve()
    assert file.is_file(), f"{case.name}: {expect['file']} is no file of {root}"
    substituted = {file: (case / expect["file"]).read_text(encoding="utf-8")}
    if expect["stage"] == "verify":
        return file, verify([file], [root], substituted=substituted).diagnostics
    return file, check([file], [root], substituted=substituted).diagnostics.items


def test_the_corpus_covers_many_kinds_several_times() -> None:
    cases = _cases()
    codes = [_expect(c)["code"] for c in cases]
    assert len(cases) >= MINIMUM_CASES
    assert len(set(codes)) >= MINIMUM_KINDS
    assert all(codes.count(code) >= 2 for code in codes), "each kind is broken twice or more"
    charts = {(_expect(c)["code"], _expect(c).get("root"), _expect(c)["file"]) for c in cases}
    assert len(charts) == len(cases), "each instance of a kind breaks another chart"


@pytest.mark.parametrize("case", _cases(), ids=lambda case: case.name)
def test_the_broken_model_is_found_at_its_cause(case: Path) -> None:
    expect = _expect(case)
    file, findings = _findings(case)
    where = [(d.code, d.line, d.column) for d in findings if Path(d.file).resolve() == file]
    assert (expect["code"], expect["line"], expect["column"]) in where, where
