"""The defaults of scene object attributes are typed like parameter defaults.

They initialise the environment model that guards read before any component has written it,
so a default of the wrong type would surface only at run time, or differently on each target.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.workbench.check import check

CELL = """package t;

<<scene="none">> cell Bench {{
  object part {{
    {attribute}
  }}
  object other;
}}
"""

FITTING = [
    "Boolean seated = false;",
    "Integer tries = 2 * 3 - 1;",
    "Integer offset = -2;",
    "Real share = 1;",
    "Real share = 0.5;",
    "Length gap = -2 mm;",
    "Length gap = 2 * 3 mm + 1 cm;",
    "Angle turn = 90 deg;",
    "Length gap = max(1 mm, 2 mm);",
    "Integer tries;",
]

MISFITTING = [
    ("Boolean seated = 3;", "LR0302", "default of 'part.seated': expected Boolean, found Integer"),
    ("Integer tries = 2.5;", "LR0308", "default of 'part.tries': expected Integer, found Real"),
    ("Integer tries = 4 / 2;", "LR0308", "default of 'part.tries': expected Integer, found Real"),
    ("Length gap = 5 s;", "LR0304", "default of 'part.gap': expected Length [m], found s [s]"),
    ("Angle turn = 3 mm;", "LR0304", "default of 'part.turn': expected Angle"),
    ("Boolean seated = other;", "LR0103", "'other'"),
]


def _write(root: Path, attribute: str) -> Path:
    path = root / "t" / "Bench.lrd"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(CELL.format(attribute=attribute), encoding="utf-8")
    return path


def _findings(root: Path) -> list[tuple[str, int, int, str]]:
    context = check([root / "t"], [root])
    return [(d.code, d.line, d.column, d.message) for d in context.diagnostics.items]


@pytest.mark.parametrize("attribute", FITTING)
def test_a_default_of_the_attribute_type_is_accepted(tmp_path: Path, attribute: str) -> None:
    _write(tmp_path, attribute)
    assert _findings(tmp_path) == []


@pytest.mark.parametrize(("attribute", "code", "says"), MISFITTING)
def test_a_default_of_another_type_is_reported_at_the_default(
    tmp_path: Path, attribute: str, code: str, says: str
) -> None:
    _write(tmp_path, attribute)
    [(found, line, column, message)] = _findings(tmp_path)
    assert (found, line) == (code, 5)
    assert column == 5 + attribute.index("=") + 2
    assert says in message


def test_the_command_line_reports_a_misfitting_default_with_exit_code_1(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    path = _write(tmp_path, "Integer tries = 2.5;")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    assert main(["check", "t"]) == 1
    out = capsys.readouterr().out
    assert f"{path.relative_to(tmp_path)}:5:21: error LR0308" in out
