"""An incremental re-check after edits reports exactly what a full check reports."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from lightrocks.workbench.check import check
from lightrocks.workbench.incremental import IncrementalCheck

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture
def screwing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    shutil.copytree(EXAMPLES, tmp_path / "examples")
    return tmp_path / "examples"


def full_findings(root: Path, texts: dict[Path, str]) -> list:
    return check([root], (), {p.resolve(): t for p, t in texts.items()}).diagnostics.items


def edits(root: Path) -> list[tuple[Path, str]]:
    """Breaking and repairing edits of a cell, an action and a skill of the screwing example."""
    files = sorted((root / "screwing").rglob("*.lr*"))
    chosen = [files[0], files[len(files) // 2], files[-1]]
    result = []
    for file in chosen:
        text = file.read_text(encoding="utf-8")
        result.append((file, text.replace("state ", "state X", 1)))  # renames a state
        result.append((file, text[: len(text) // 2]))  # a syntax error
        result.append((file, text.replace("{", "{ ", 1) + "\n"))  # same meaning, new content
        result.append((file, text))  # repaired
    return result


def test_each_edit_matches_a_full_check(screwing: Path) -> None:
    incremental = IncrementalCheck([screwing])
    assert incremental.full() == full_findings(screwing, {})
    texts: dict[Path, str] = {}
    for file, text in edits(screwing):
        texts[file] = text
        assert incremental.update({file: text}) == full_findings(screwing, texts), file


def test_an_edit_rechecks_only_dependent_files(screwing: Path) -> None:
    incremental = IncrementalCheck([screwing])
    incremental.full()
    leaf = next(p for p in incremental.graph if not any(incremental.graph.predecessors(p)))
    incremental.update({leaf: leaf.read_text(encoding="utf-8") + "\n"})
    assert incremental.rechecked < set(incremental.graph)


def test_fixing_an_imported_chart_clears_findings_of_importers(screwing: Path) -> None:
    incremental = IncrementalCheck([screwing])
    clean = incremental.full()
    imported = next(
        p for p in incremental.graph if p.suffix == ".lr" and any(incremental.graph.predecessors(p))
    )
    text = imported.read_text(encoding="utf-8")
    broken = incremental.update({imported: text[: len(text) // 2]})
    assert broken != clean
    assert incremental.update({imported: None}) == clean


MEANING_EDITS = [
    # (file below examples/, old, new): each keeps the names the file declares
    ("screwing/cell/ScrewingCell.lrd", "Integer cycles = 0;", "Length cycles = 0 mm;"),
    ("din_rail/cell/RailCell.lrd", "object terminal3", "object clip3"),
    ("din_rail/actions/Seat.lr", "end condition", "end condition moved; end condition"),
    ("din_rail/skills/CarryToSlot.lr", "end condition above;", "end condition over;"),
    ("din_rail/skills/SnapOnRail.lr", "parameters {", "parameters {\n    Integer extra;"),
    ("screwing/actions/TurnTool.lr", "end condition", "end condition stuck; end condition"),
]


@pytest.mark.parametrize(("file", "old", "new"), MEANING_EDITS, ids=[e[0] for e in MEANING_EDITS])
def test_an_edit_of_what_a_declaration_means_reaches_its_users(
    screwing: Path, file: str, old: str, new: str
) -> None:
    incremental = IncrementalCheck([screwing])
    clean = incremental.full()
    path = (screwing / file).resolve()
    text = path.read_text(encoding="utf-8")
    assert old in text
    edited = text.replace(old, new, 1)
    found = incremental.update({path: edited})
    assert found == full_findings(screwing, {path: edited})
    assert found != clean  # the edit changed what some file means
    assert incremental.rechecked < set(incremental.graph)  # not a full check in disguise
    assert incremental.update({path: None}) == full_findings(screwing, {})
