"""Check and run judge a value by one implementation (runtime.safety): the check of a constant
and the refusal of a value computed at run time give the same verdict and the same message,
and neither takes NaN for safe.

The language cannot write a NaN constant (a number literal is digits, and constant folding
drops any result that is not finite), so the check's side is tested on its API with a NaN
literal built directly; an infinite literal (``1e400 mm``) it can write, and both refuse it.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.cli import main
from lightrocks.app.loading import load_component
from lightrocks.languages.domain.ranges import Range
from lightrocks.metamodel import ast
from lightrocks.runtime.binding import bind

MM = 0.001
DEPTH = Range("arm", "move", "x", ast.Quantity(0.0, "mm", "0"), ast.Quantity(50 * MM, "mm", "50"))
STIFFNESS = Range(
    "arm",
    "move",
    "k",
    ast.VectorLiteral((ast.Quantity(0.0, "N/m", "0"), ast.Quantity(0.0, "N/m", "0"))),
    ast.VectorLiteral((ast.Quantity(500.0, "N/m", "500"), ast.Quantity(500.0, "N/m", "500"))),
)

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
  do / arm.move(x = x * 2);
  end condition reached [arm.goalReached];
}
"""


def quantity(number: float) -> ast.Quantity:
    return ast.Quantity(number * MM, "mm", f"{number}")


@pytest.mark.parametrize("number", [0.0, 50.0, 60.0, -1.0, math.inf, -math.inf, math.nan])
def test_the_check_gives_the_runs_verdict_and_message(number: float) -> None:
    runtime = DEPTH.safe_range()
    assert runtime is not None
    assert DEPTH.breach(quantity(number)) == runtime.breach(number * MM)


def test_the_check_refuses_nan() -> None:
    assert DEPTH.breach(quantity(math.nan)) == (
        "arm.move(x) = nan mm is outside its safe range 0 mm .. 50 mm"
    )
    nan_element = ast.VectorLiteral((ast.Quantity(1.0, "N/m", "1"), ast.Quantity(math.nan, "N/m")))
    assert "arm.move(k[1]) = nan N/m is outside" in STIFFNESS.breach(nan_element)


def test_an_unconstrained_or_unknown_value_is_no_finding() -> None:
    unbounded = Range("arm", "move", "x", ast.Name("low"), None)
    assert unbounded.safe_range() is None
    assert unbounded.breach(quantity(math.nan)) is None
    assert DEPTH.breach(ast.Name("depth")) is None


@pytest.fixture
def move(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> type:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    (tmp_path / "t").mkdir()
    (tmp_path / "t" / "Cell.lrd").write_text(CELL, encoding="utf-8")
    (tmp_path / "t" / "Move.lr").write_text(MOVE, encoding="utf-8")
    return load_component(tmp_path / "t" / "Move.lr", [tmp_path])


@pytest.mark.parametrize("x", [math.nan, math.inf])
def test_the_run_refuses_a_computed_nan_or_infinity(move: type, x: float) -> None:
    adapter = DryRunAdapter()
    bind(adapter, move.CELL)
    chart = move(x=x)
    chart.start(adapter)
    assert chart.outcome == "error"
    assert f"refused: arm.move(x) = {x / MM:g} mm is outside its safe range" in chart.fault.message


def test_the_check_refuses_an_infinite_literal(
    move: type, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    chart = tmp_path / "t" / "Move.lr"
    chart.write_text(MOVE.replace("x = x * 2", "x = 1e400 mm"), encoding="utf-8")
    assert main(["check", str(chart), "--path", str(tmp_path)]) == 1
    assert "arm.move(x) = inf mm is outside its safe range 0 mm .. 50 mm" in capsys.readouterr().out
