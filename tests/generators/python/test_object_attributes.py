"""Scene object attributes in the Python target: a default initialises the attribute, and an
attribute without one starts at zero, false or empty, as a PLC variable does."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.cli import main

CELL = """package t;

vector Pair of Integer [2];

<<scene="none">> cell Bench {
  object part {
    Integer tries;
    Real share;
    Boolean seated;
    Length gap;
    Pair pair;
    String label;
    Frame where;
    Integer set = 2 * 2;
  }
}
"""

TASK = """package t;

import t.Bench;

statechart Task {
  initial state A;
  final state Zeroed;
  final state Other;
  A -> Zeroed [GUARD] go;
  A -> Other stop;
}
"""

GUARD = (
    "part.tries == 0 && part.share == 0 && !part.seated && part.gap == 0 mm"
    ' && part.pair[0] == 0 && part.pair[1] == 0 && part.label == "" && part.set == 4'
)


def test_attributes_without_default_start_at_zero(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "t").mkdir()
    (tmp_path / "t" / "Bench.lrd").write_text(CELL, encoding="utf-8")
    (tmp_path / "t" / "Task.lr").write_text(TASK.replace("GUARD", GUARD), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert main(["run", "t/Task.lr", "--path", ".", "--events", "go"]) == 0
    out = capsys.readouterr().out
    assert "outcome: Zeroed" in out
