"""Defaults in the SFC target: initial values that the runtime would compute.

A parameter's default initialises its input, and a scene object's attribute defaults
initialise the object's global, folded to constants as the runtime computes them. A default
that is not constant has no initial value to become: generation stops with its place rather
than start the PLC from zero. MatIEC steps such defaults in test_matiec.py (model Dial).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import generate

from lightrocks.app.cli import main

CHART = """package t;

statechart Mix {{
  parameters {{
    {parameters}
  }}
  initial state A;
}}
"""

CELL = """package t;

<<scene="none">> cell Bench {
  object part {
    Integer tries = 2 * 3 - 1;
    Boolean seated = !(1 > 2);
    Length gap = -2 mm + 1 cm;
    Real share;
  }
  object spare;
}
"""

TASK = """package t;

import t.Bench;

statechart Task {
  initial state A;
  final state B;
  A -> B [part.tries == 5] go;
}
"""


def _write(root: Path, name: str, text: str) -> Path:
    path = root / "t" / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(
    ("declaration", "input"),
    [
        ("Integer tries = 2 * 3 - 1;", "tries : DINT := 5;"),
        ("Integer rest = -(7 % 3);", "rest : DINT := -1;"),
        ("Real ratio = 7 / 2;", "ratio : REAL := 3.5;"),
        ("Real ratio = 2;", "ratio : REAL := 2.0;"),
        ("Length reach = 2 mm + 1 cm;", "reach : REAL := 0.012;"),
        ("Boolean armed = 1 < 2 && !(3 == 4);", "armed : BOOL := TRUE;"),
        ("Real ratio = min(3, 0.5) * 4;", "ratio : REAL := 2.0;"),
    ],
)
def test_a_parameter_default_is_folded_into_the_initial_value(
    tmp_path: Path, declaration: str, input: str
) -> None:
    model = _write(tmp_path, "Mix.lr", CHART.format(parameters=declaration))
    text = generate("sfc", [model], search=[tmp_path])["Mix.st"]
    assert f"  {input}" in text


def test_object_attribute_defaults_initialise_the_objects_global(tmp_path: Path) -> None:
    _write(tmp_path, "Bench.lrd", CELL)
    model = _write(tmp_path, "Task.lr", TASK)
    text = generate("sfc", [model], search=[tmp_path])["Task.st"]
    initial = "(tries := 5, seated := TRUE, gap := 0.008)"
    assert f"  part : SceneObject := {initial};" in text
    assert "  spare : SceneObject;" in text


def test_a_default_that_is_not_constant_stops_generation_at_its_place(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    parameters = "Integer tries = 2;\n    Integer more = tries + 1;"
    model = _write(tmp_path, "Mix.lr", CHART.format(parameters=parameters))
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "out"
    code = main(["generate", str(model), "--target", "sfc", "-o", str(out), "--path", "."])
    assert code == 1
    error = capsys.readouterr().err
    assert "Mix.lr:6:20" in error
    assert "the SFC target needs a constant default for 'more' of t.Mix" in error
    assert "Traceback" not in error
    assert not out.exists() or not any(out.iterdir())
