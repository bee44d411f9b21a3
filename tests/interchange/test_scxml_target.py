"""``lightrocks generate --target scxml`` (docs/interchange.md, section SCXML): what it writes
and what it refuses, each refusal at the construct's file:line:col with nothing written."""

from __future__ import annotations

import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from interchange.scxml_judge import Machine, simulated
from lightrocks.generators.scxml.chart_tree import Refusal
from lightrocks.generators.scxml.writer import Writer
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.languages.scxml.markup import LR, SCXML
from lightrocks.metamodel import ast

ROOT = Path(__file__).resolve().parents[2]
PLANT = ROOT / "tests" / "generators" / "models"


def _lightrocks(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "lightrocks.app.cli", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        check=False,
    )


def _document(text: str):
    unit = parse_statechart(text, "d/A.lr")
    return Writer(unit, ast.stereotype(unit.statechart.stereotypes, "timeout")).document()


def test_generate_writes_one_document_per_plain_chart(tmp_path: Path) -> None:
    out = tmp_path / "out"
    models = [str(PLANT / "plant" / f"{n}.lr") for n in ("Lamp", "Player")]
    done = _lightrocks(
        "generate", *models, "--path", str(PLANT), "--target", "scxml", "-o", str(out)
    )
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in out.iterdir()) == ["Lamp.scxml", "Player.scxml"]
    root = ET.parse(out / "Lamp.scxml").getroot()
    assert root.tag == f"{{{SCXML}}}scxml" and root.get("datamodel") == "python"
    again = tmp_path / "again"
    _lightrocks("generate", *models, "--path", str(PLANT), "--target", "scxml", "-o", str(again))
    assert (again / "Lamp.scxml").read_bytes() == (out / "Lamp.scxml").read_bytes()


def test_generate_refuses_a_component_and_writes_nothing(tmp_path: Path) -> None:
    out = tmp_path / "out"
    models = [str(PLANT / "plant" / f"{n}.lr") for n in ("Lamp", "Batch")]
    done = _lightrocks(
        "generate", *models, "--path", str(PLANT), "--target", "scxml", "-o", str(out)
    )
    assert done.returncode == 1
    assert "plant/Batch.lr:5:1: the scxml target takes plain statecharts" in done.stderr
    assert not out.exists()


CHART = """package d;

statechart A {{
  parameters {{
    Integer n = 0;
  }}

  initial state S;
  state T;
{extra}
}}
"""

REFUSED = [
    ("  state U { do / n = 1; }", "a 'do' action", (10, 13)),
    ("  start condition go;", "a start condition", (10, 3)),
    ("  S -> T lock(1234);", "an event's arguments", (10, 10)),
    ("  S -> T after(n * 100 ms);\n  T -> S go / { n = n + 1; };", "after(n * 100 ms)", (10, 16)),
    ("  S -> T [rotX(1) == n] go;", "a call of 'rotX'", (10, 11)),
    ("  S -> T [bin.items > 0] go;", "a member access", (10, 14)),
    ("  S -> T go / { n = [1, 2]; };", "a vector", (10, 21)),
    ('  <<import="B">> state U;', "<<import>>", (10, 5)),
    ("  end condition done [n > 1];", "an end condition with a condition", (10, 3)),
    ("  S -> T timeout;", "the outcome 'timeout'", (10, 10)),
]


@pytest.mark.parametrize(("extra", "words", "where"), REFUSED, ids=[r[1] for r in REFUSED])
def test_each_construct_without_counterpart_is_refused_at_its_place(
    extra: str, words: str, where: tuple[int, int]
) -> None:
    with pytest.raises(Refusal) as refused:
        _document(CHART.format(extra=extra))
    problem = refused.value
    assert words in problem.message
    assert (problem.position.line, problem.position.column) == where
    assert str(problem).startswith(f"d/A.lr:{where[0]}:{where[1]}: ")


def test_every_refusal_of_a_chart_is_counted(tmp_path: Path) -> None:
    (tmp_path / "d").mkdir()
    chart = CHART.format(extra="  S -> T lock(1);\n  T -> S after(n * 1 s) / { n = 2; };")
    (tmp_path / "d" / "A.lr").write_text(chart, encoding="utf-8")
    out = tmp_path / "out"
    done = _lightrocks("generate", "d/A.lr", "--target", "scxml", "-o", "out", cwd=tmp_path)
    assert done.returncode == 1 and not out.exists()
    assert "d/A.lr:10:10: scxml: an event's arguments" in done.stderr
    assert "(1 more construct(s) the target cannot express)" in done.stderr


def test_a_delay_of_parameters_the_chart_never_assigns_is_computed_from_their_defaults() -> None:
    text = (PLANT / "plant" / "Hopper.lr").read_text(encoding="utf-8")
    document = _document(text)
    assert 'delay="300ms"' in document.text
    assert "after(pause * 100 ms) at d/A.lr:34:25: the chart never assigns pause" in document.text


NAMES = """package d;

statechart A {
  events {
    done;
    error;
  }

  parameters {
    Integer model = 1;
    Integer event = 2;
    Integer lambda = 3;
    Integer lr_done_P = 4;
    String text = "true && 'x' & <y>";
  }

  initial state P {
    initial state Q;
    final state F;
    history H;
    Q -> F done;
  }
  state null;

  P -> null error;
  null -> P.H done [text == "true && 'x' & <y>"];
  P -> null;
}
"""


def test_names_that_scxml_or_the_data_model_reserve_are_renamed() -> None:
    document = _document(NAMES)
    root = ET.fromstring(document.text)
    data = {
        d.get(f"{{{LR}}}name") or d.get("id"): d.get("id") for d in root.iter(f"{{{SCXML}}}data")
    }
    assert data == {
        "model": "v_model",
        "event": "v_event",
        "lambda": "v_lambda",
        "lr_done_P": "lr_done_P",
        "text": "text",
        "lr_done_P_2": "lr_done_P_2",
    }
    events = {t.get("event") for t in root.iter(f"{{{SCXML}}}transition")}
    assert {"done-event", "lr-error.A-P"} <= events and "done" not in events
    assert document.paths["A-null_"] == ("A", "null")


def test_reserved_names_and_strings_run_in_python_statemachine() -> None:
    document = _document(NAMES)
    with simulated():
        machine = Machine(document, ["model", "text"])
        machine.send("done")
        assert machine.observation() == (("A", "A/null"), (1, "true && 'x' & <y>"))
        machine.send("done")
        assert machine.observation() == (("A", "A/P", "A/P/Q"), (1, "true && 'x' & <y>"))


def test_the_data_model_has_no_call_but_in() -> None:
    """abs, min and max are written as arithmetic on comparisons, and give what the runtime
    gives for Integers, Reals and signs."""
    chart = """package d;

statechart A {
  parameters {
    Integer a = -3;
    Real b = 2.5;
    Integer c = 0;
    Real d = 0;
  }

  initial state S;
  state T;
  S -> T go / { c = abs(a) + min(a, 2) * max(4, a); d = min(b, a) + max(b, 7) + abs(-b); };
}
"""
    document = _document(chart)
    assert "abs(" not in document.text and "min(" not in document.text
    with simulated():
        machine = Machine(document, ["c", "d"])
        machine.send("go")
        assert machine.observation()[1] == (3 + -3 * 4, -3 + 7 + 2.5)
