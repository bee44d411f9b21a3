"""Positions carry the end the parse tree records: every node's span is exactly its text,
while findings and positions are still told apart, shown and ordered by their start."""

from __future__ import annotations

from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Diagnostic, Diagnostics, Severity
from lightrocks.workbench.languages import language_for

MODEL = """\
<<action>> statechart Probe {
  parameters {
    Length depth = 12 mm;
  }
  end condition done;
  // a comment with an emoji 🤖 before the states
  initial state Touch(limit = abs(depth - 2 mm) * 3);
  <<import="Probe">> state Again {
    entry / { x = robot.wrench.force.z; }
  }
  Touch -> done [depth > 1 mm && depth <= 2 mm];
}
"""


def _text_of(position: ast.Position) -> str:
    """The source text a position spans."""
    lines = MODEL.split("\n")
    if position.line == position.end_line:
        return lines[position.line - 1][position.column - 1 : position.end_column - 1]
    first = lines[position.line - 1][position.column - 1 :]
    middle = lines[position.line : position.end_line - 1]
    last = lines[position.end_line - 1][: position.end_column - 1]
    return "\n".join([first, *middle, last])


def _spans() -> dict[str, list[str]]:
    unit = language_for(".lr").parse(MODEL, "Probe.lr")
    found: dict[str, list[str]] = {}
    for node in ast.walk(unit):
        position = getattr(node, "position", None)
        if isinstance(position, ast.Position) and position.has_end:
            found.setdefault(type(node).__name__, []).append(_text_of(position))
    return found


def test_names_literals_and_calls_span_their_text() -> None:
    spans = _spans()
    assert "depth" in spans["Name"] and "robot" in spans["Name"]
    assert {"12 mm", "2 mm", "3", "1 mm"} <= set(spans["Quantity"])
    assert "abs(depth - 2 mm)" in spans["Call"]
    assert ".z" in spans["Member"]  # a member starts at its dot, as its findings do


def test_a_binary_expression_ends_with_its_right_operand() -> None:
    binaries = _spans()["Binary"]
    assert "abs(depth - 2 mm) * 3" in binaries
    assert "depth - 2 mm" in binaries
    assert "depth > 1 mm && depth <= 2 mm" in binaries
    assert "depth <= 2 mm" in binaries


def test_declarations_span_from_their_stereotypes_to_their_end() -> None:
    spans = _spans()
    assert "initial state Touch(limit = abs(depth - 2 mm) * 3);" in spans["State"]
    again = next(s for s in spans["State"] if s.startswith("<<import"))
    assert again.endswith("}") and "entry" in again
    assert "Length depth = 12 mm;" in spans["Parameter"]
    assert "Touch -> done [depth > 1 mm && depth <= 2 mm];" in spans["Transition"]


def test_columns_count_code_points_after_a_character_outside_the_bmp() -> None:
    unit = language_for(".lr").parse(MODEL, "Probe.lr")
    touch = next(n for n in ast.walk(unit) if isinstance(n, ast.State) and n.name == "Touch")
    line = MODEL.split("\n")[touch.position.line - 1]
    assert touch.position.column == line.index("initial") + 1
    assert touch.position.end_column == len(line) + 1


def test_the_end_changes_neither_equality_nor_the_text_shown() -> None:
    short = ast.Position("A.lr", 3, 5, 3, 9)
    long = ast.Position("A.lr", 3, 5, 7, 2)
    assert short == long and hash(short) == hash(long)
    assert str(long) == "A.lr:3:5"
    first = Diagnostic.at(short, "LR0001", Severity.ERROR, "broken")
    assert (first.end_line, first.end_column) == (3, 9)
    assert str(first) == "A.lr:3:5: error LR0001: broken"
    findings = Diagnostics()
    findings.error(short, "LR0001", "broken")
    findings.error(long, "LR0001", "broken")
    assert len(findings.items) == 1


def test_a_node_made_of_parts_spans_from_the_first_to_the_last() -> None:
    start, last = ast.Position("A.lr", 1, 3, 1, 8), ast.Position("A.lr", 2, 1, 2, 6)
    assert start.through(last) == start
    assert (start.through(last).end_line, start.through(last).end_column) == (2, 6)


def test_uml_p_statecharts_carry_ends_too() -> None:
    source = "statechart Door {\n  initial state Shut;\n  Shut -> Open [a + b(1) > 2];\n}\n"
    unit = language_for(".sc").parse(source, "Door.sc")
    lines = source.split("\n")
    spans = {
        lines[p.line - 1][p.column - 1 : p.end_column - 1]
        for node in ast.walk(unit)
        if isinstance(p := getattr(node, "position", None), ast.Position)
        and p.has_end
        and p.line == p.end_line
    }
    assert {"initial state Shut;", "a + b(1) > 2", "b(1)"} <= spans
