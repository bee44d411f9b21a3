"""Integers and Reals in the typing pass, as in Java and as both targets compute them.

``3`` is an Integer literal, ``3.0``, ``0.5`` and ``1e3`` are Real ones; ``+ - * %`` of two
Integers give an Integer, ``/`` and any Real operand give a Real. An Integer widens to a
Real; a Real where an Integer is declared is LR0308, at the place the SFC target refuses it.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.languages.domain.types import describe
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.metamodel import ast
from lightrocks.workbench.check import check

MARK = "@@"

DOMAIN = """package t;

vector Counts of Integer [2];

device Scale {
  command weigh(Integer rounds = 2, Real factor = 1);
  command measure() returns Real;
  command tally() returns Integer;
  sensor Boolean done;
}

<<scene="none">> cell Bench {
  scale : Scale;
}
"""

WEIGH = """package t;

import t.Bench;

<<action>> statechart Weigh {
  parameters { Integer rounds = 2; Real factor = 1; }
  do / scale.weigh(rounds = rounds, factor = factor);
  end condition settled [scale.done];
}
"""

STORE = """package t;

import t.Bench;

<<action>> statechart Store {
  parameters { Integer whole = 0; Real share = 0; }
  do / {statement}
  end condition settled [scale.done];
}
"""

MIX = """package t;

import t.Bench;

<<skill>> statechart Mix {
  parameters {
    Integer n = 3;
    Integer m = 2;
    Real r = 0.5;
    Length x = 1 mm;
    Counts c = [1, 2];
    {parameters}
  }
  entry / { {statements} }
  {states}
  start condition go;
  end condition done;
  go -> A;
  A -> done settled;
}
"""


def write(root: Path, name: str, text: str) -> tuple[Path, tuple[int, int] | None]:
    """Writes ``t/<name>``; returns its path and the line and column of the ``@@`` marker."""
    place = None
    if MARK in text:
        before = text[: text.index(MARK)]
        place = (before.count("\n") + 1, len(before) - before.rfind("\n"))
        text = text.replace(MARK, "", 1)
    path = root / "t" / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path, place


def model_set(
    root: Path,
    parameters: str = "",
    statements: str = "",
    states: str = "state A;",
    store: str = "whole = scale.tally();",
) -> dict[str, tuple[Path, tuple[int, int] | None]]:
    files = {
        "Bench.lrd": DOMAIN,
        "Weigh.lr": WEIGH,
        "Store.lr": STORE.replace("{statement}", store),
        "Mix.lr": MIX.replace("{parameters}", parameters)
        .replace("{statements}", statements)
        .replace("{states}", states),
    }
    return {name: write(root, name, text) for name, text in files.items()}


def findings(root: Path) -> list[tuple[str, str, int, int]]:
    context = check([root / "t"], [root])
    return [(d.code, Path(d.file).name, d.line, d.column) for d in context.diagnostics.items]


# -- result types ---------------------------------------------------------------------------

RESULTS = [
    ("n + m", "Integer"),
    ("n - m", "Integer"),
    ("n * m", "Integer"),
    ("n % m", "Integer"),
    ("n / m", "Real"),
    ("7 / 2", "Real"),
    ("2 * 3 - 1", "Integer"),
    ("0.5 + n", "Real"),
    ("n + 0.5", "Real"),
    ("n * r", "Real"),
    ("r * n", "Real"),
    ("r % n", "Real"),
    ("n - r", "Real"),
    ("3", "Integer"),
    ("3.0", "Real"),
    ("0.5", "Real"),
    ("1e3", "Real"),
    ("-n", "Integer"),
    ("-2", "Integer"),
    ("abs(n)", "Integer"),
    ("abs(r)", "Real"),
    ("min(n, m)", "Integer"),
    ("min(n, 0.5)", "Real"),
    ("max(r, m)", "Real"),
    ("n * 1 mm / (1 mm)", "Real"),
    ("n * 2 mm", "Length [m]"),
    ("x + n * 2 mm", "Length [m]"),
    ("3 mm", "mm [m]"),
]


def test_every_mix_has_its_result_type(tmp_path: Path) -> None:
    statements = " ".join(f"{'x' if t.endswith('[m]') else 'r'} = {e};" for e, t in RESULTS)
    model_set(tmp_path, statements=statements)
    context = check([tmp_path / "t"], [tmp_path])
    assert context.diagnostics.items == []
    typing = analysis(context).typing
    types = {id(e): t for found in typing.inferred.values() for e, t in found}
    [mix] = [c for c in analysis(context).models.components if c.name == "Mix"]
    [entry] = [a for a in mix.region.actions if a.kind == "entry"]
    values = [s.value for s in entry.statements if isinstance(s, ast.Assignment)]
    written = [e for e, _ in RESULTS]
    found = [(e, describe(types[id(v)])) for e, v in zip(written, values, strict=True)]
    assert found == RESULTS


def test_a_computed_quantity_is_named_after_the_library_type_of_its_dimension(
    tmp_path: Path,
) -> None:
    model_set(tmp_path, parameters="Time t = x / 2 s; Force f = x * x;")
    messages = [d.message for d in check([tmp_path / "t"], [tmp_path]).diagnostics.items]
    assert messages == [
        "default of 't': expected Time [s], found Velocity [m/s]",
        "default of 'f': expected Force [m·kg/s^2], found quantity [m^2]",
    ]


# -- a Real where an Integer is declared ----------------------------------------------------

NARROWING = [
    ("Integer whole = @@2.5;", "", "state A;", "Mix.lr"),
    ("Integer whole = @@4.0;", "", "state A;", "Mix.lr"),
    ("Integer whole = @@1e3;", "", "state A;", "Mix.lr"),
    ("Integer whole = @@n / m;", "", "state A;", "Mix.lr"),
    ("", "n = @@n / m;", "state A;", "Mix.lr"),
    ("", "n = @@0.5 + n;", "state A;", "Mix.lr"),
    ("", "m = @@r;", "state A;", "Mix.lr"),
    ("", "m = @@max(n, r);", "state A;", "Mix.lr"),
    ("", "c = @@[n, 0.5];", "state A;", "Mix.lr"),
    ("", "", '<<import="Weigh">> state A(rounds = @@r);', "Mix.lr"),
    ("", "", '<<import="Weigh">> state A(@@n * 0.5);', "Mix.lr"),
]


@pytest.mark.parametrize(("parameters", "statements", "states", "file"), NARROWING)
def test_a_real_where_an_integer_is_declared_is_reported_at_its_place(
    tmp_path: Path, parameters: str, statements: str, states: str, file: str
) -> None:
    files = model_set(tmp_path, parameters, statements, states)
    line, column = files[file][1]
    assert findings(tmp_path) == [("LR0308", file, line, column)]


@pytest.mark.parametrize(
    "store",
    ["scale.weigh(rounds = @@0.5);", "scale.weigh(@@2 * 0.5, 1);", "@@whole = scale.measure();"],
)
def test_device_commands_take_and_return_no_real_for_an_integer(tmp_path: Path, store: str) -> None:
    files = model_set(tmp_path, store=store)
    line, column = files["Store.lr"][1]
    assert findings(tmp_path) == [("LR0308", "Store.lr", line, column)]


def test_the_finding_names_both_types_and_how_to_mend_it(tmp_path: Path) -> None:
    model_set(tmp_path, statements="n = n / m;")
    [diagnostic] = check([tmp_path / "t"], [tmp_path]).diagnostics.items
    assert diagnostic.message == (
        "assigned value: expected Integer, found Real: a Real value does not fit an Integer"
    )
    assert "declare the target Real" in diagnostic.hint


def test_an_integer_widens_to_a_real(tmp_path: Path) -> None:
    model_set(
        tmp_path,
        parameters="Real share = n; Real half = 1;",
        statements="r = n; r = n / m; half = n % m; x = n * 1 mm; n = n * m + 1 - n % 2;",
        states='<<import="Weigh">> state A(rounds = n * 2, factor = n);',
        store="share = scale.tally();",
    )
    assert findings(tmp_path) == []


def test_quantities_keep_their_dimension_checks(tmp_path: Path) -> None:
    files = model_set(tmp_path, statements="x = @@n * 2 s;")
    line, column = files["Mix.lr"][1]
    assert findings(tmp_path) == [("LR0304", "Mix.lr", line, column)]


def test_the_cli_reports_it_with_exit_code_1_and_no_traceback(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    files = model_set(tmp_path, statements="n = @@n / 2;")
    line, column = files["Mix.lr"][1]
    status = main(["check", str(tmp_path / "t"), "--path", str(tmp_path)])
    out, err = capsys.readouterr()
    assert status == 1
    assert f"Mix.lr:{line}:{column}: error LR0308: assigned value" in out
    assert "Traceback" not in out + err


def test_a_real_default_of_an_integer_command_parameter_is_lr0404(tmp_path: Path) -> None:
    model_set(tmp_path)
    domain = DOMAIN.replace("Integer rounds = 2,", "Integer rounds = @@2.5,")
    _, (line, column) = write(tmp_path, "Bench.lrd", domain)
    context = check([tmp_path / "t"], [tmp_path])
    [diagnostic] = context.diagnostics.items
    assert (diagnostic.code, Path(diagnostic.file).name) == ("LR0404", "Bench.lrd")
    assert (diagnostic.line, diagnostic.column) == (line, column)
    assert diagnostic.message == "'rounds' expects Integer, not a Real value"


@pytest.mark.parametrize("bounds", ["in @@0.5 .. 10", "in 0 .. @@9.5"])
def test_a_real_safe_range_bound_of_an_integer_command_parameter_is_lr0404(
    tmp_path: Path, bounds: str
) -> None:
    model_set(tmp_path)
    domain = DOMAIN.replace("Integer rounds = 2,", f"Integer rounds = 2 {bounds},")
    _, (line, column) = write(tmp_path, "Bench.lrd", domain)
    context = check([tmp_path / "t"], [tmp_path])
    [diagnostic] = context.diagnostics.items
    assert (diagnostic.code, diagnostic.line, diagnostic.column) == ("LR0404", line, column)
    assert diagnostic.message == "'rounds' expects Integer, not a Real value"
