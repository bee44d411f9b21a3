"""A value only known at run time that lies outside a command's safe range: the command is
refused, the run ends in ``error`` naming the device, command, element and range."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from lightrocks.workbench.app.cli import main

CELL = """package t;

<<timeout="2 s">> device Arm {
  command move(Length x in 0 mm .. 50 mm);
  sensor Boolean goalReached;
}

<<scene="none">> cell Cell {
  arm : Arm;
}
"""

MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  parameters { Length x = 10 mm; }
  do / arm.move(x = x);
  end condition reached [arm.goalReached];
}
"""


@pytest.fixture(autouse=True)
def cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "xdg"))


@pytest.fixture
def model(tmp_path: Path) -> list[str]:
    (tmp_path / "t").mkdir()
    (tmp_path / "t" / "Cell.lrd").write_text(CELL, encoding="utf-8")
    (tmp_path / "t" / "Move.lr").write_text(MOVE, encoding="utf-8")
    return [str(tmp_path / "t" / "Move.lr"), "--path", str(tmp_path), "--adapter", "dryrun"]


def test_out_of_range_run_value_is_refused(
    model: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    trace = tmp_path / "trace.jsonl"
    status = main(["run", *model, "--param", "x=100mm", "--trace", str(trace)])
    out = capsys.readouterr().out
    assert status == 1
    assert "outcome: error" in out
    assert "refused: arm.move(x) = 0.1 is outside the safe range [0] .. [0.05]" in out
    assert "via Move" in out
    records = [json.loads(line) for line in trace.read_text(encoding="utf-8").splitlines()]
    assert records[-1] == {"time": 0.0, "kind": "finished", "outcome": "error"}


def test_in_range_run_value_runs(model: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["run", *model, "--param", "x=20mm"]) == 0
    assert "outcome: reached" in capsys.readouterr().out
