"""Completion transitions, outcomes and external events get consistent findings."""

from __future__ import annotations

from pathlib import Path

from lightrocks.workbench.check import check

PROCESS = """package misc;

statechart Line {
  initial state Idle;
  state Process {
    initial state Work;
    final state Ok;
    Work -> Ok done;
  }
  state Scrap;
  final state Shipped;

  Idle -> Process go;
  Process -> Shipped;
  Process -> Scrap bad;
  Scrap -> Idle reset;
}
"""


def _codes(tmp_path: Path, text: str) -> list[str]:
    (tmp_path / "misc").mkdir()
    (tmp_path / "misc" / "Line.lr").write_text(text)
    return [str(d) for d in check([tmp_path]).diagnostics.items]


def test_an_event_after_a_completion_is_neither_shadowed_nor_mistaken(tmp_path: Path) -> None:
    assert _codes(tmp_path, PROCESS) == []


def test_the_same_event_twice_still_never_fires(tmp_path: Path) -> None:
    extra = "  Scrap -> Idle reset;\n  Process -> Idle bad;"
    text = PROCESS.replace("  Scrap -> Idle reset;", extra)
    found = _codes(tmp_path, text)
    assert len(found) == 1 and "LR0211" in found[0] and "same event first" in found[0]


def test_a_completion_from_a_simple_state_is_reported(tmp_path: Path) -> None:
    text = PROCESS.replace("  Scrap -> Idle reset;", "  Scrap -> Idle reset;\n  Idle -> Scrap;")
    found = _codes(tmp_path, text)
    assert len(found) == 1 and "LR0214" in found[0] and ":17:3:" in found[0]
