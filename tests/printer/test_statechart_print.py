"""The canonical text of .lr models: parse -> print -> parse is equal, printing is stable."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.languages.lightrocks.printer import format_statechart_text, print_statechart
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem

MODELS = sorted((Path(__file__).parent / "models").glob("*.lr"))


@pytest.mark.parametrize("path", MODELS, ids=lambda p: p.name)
def test_round_trip_and_idempotence(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    printed = print_statechart(parse_statechart(text, path.name))
    assert parse_statechart(printed, path.name) == parse_statechart(text, path.name)
    assert print_statechart(parse_statechart(printed, path.name)) == printed
    assert format_statechart_text(printed, path.name) == printed
    assert all(len(line) <= 100 for line in printed.splitlines() if "[2000 N/m" not in line)


SCREW_IN = """\
package screwing.skills;
import screwing.cell.ScrewingCell;   import screwing.actions.*;
<<skill>> statechart ScrewIn { parameters { Length depth = 12 mm; Torque tight = 0.32 Nm; }
  start condition gripped [gripper.holding]; end condition screwed;
  <<import="TurnTool">>     state Turn(angle = turn, maxTorque = tight);
  state H { entry / { a = 1; b = 2; } H -> H; }
  gripped -> Turn; Turn -> screwed [screw.depth >= depth];
  exit / { screw.depth = screw.depth + robot.travel.z; }
}
"""

SCREW_IN_CANONICAL = """\
package screwing.skills;

import screwing.cell.ScrewingCell;
import screwing.actions.*;

<<skill>> statechart ScrewIn {
  parameters {
    Length depth = 12 mm;
    Torque tight = 0.32 Nm;
  }

  start condition gripped [gripper.holding];
  end condition screwed;

  <<import="TurnTool">> state Turn(angle = turn, maxTorque = tight);

  state H {
    entry / {
      a = 1;
      b = 2;
    }

    H -> H;
  }

  gripped -> Turn;
  Turn -> screwed [screw.depth >= depth];

  exit / { screw.depth = screw.depth + robot.travel.z; }
}
"""


def test_canonical_layout() -> None:
    assert format_statechart_text(SCREW_IN, "ScrewIn.lr") == SCREW_IN_CANONICAL


def test_long_argument_lists_break_one_per_line() -> None:
    text = (
        "statechart T { do / robot.moveCartesian(task = robot.tcp, goal = robot.tcp * "
        "rotZ(angle), stiffness = stiffness, damping = damping); }"
    )
    assert format_statechart_text(text, "T.lr") == (
        "statechart T {\n"
        "  do / robot.moveCartesian(task = robot.tcp,\n"
        "                           goal = robot.tcp * rotZ(angle),\n"
        "                           stiffness = stiffness,\n"
        "                           damping = damping);\n"
        "}\n"
    )


def test_a_built_ast_prints_quantities_from_their_si_value() -> None:
    unit = ast.StatechartUnit(
        "p",
        (ast.Import("q", wildcard=True),),
        ast.Statechart(
            "S",
            (
                ast.ParameterBlock((ast.Parameter("Length", "d", ast.Quantity(0.012, "mm")),)),
                ast.State("A", (ast.Stereotype("import", "X"),), ("initial",)),
                ast.Transition("A", "A", stimulus="e", postcondition=ast.Name("p")),
            ),
        ),
    )
    printed = print_statechart(unit)
    assert "Length d = 12 mm;" in printed
    assert "A -> A e [p];" in printed
    assert parse_statechart(printed, "S.lr") == unit


def test_syntax_errors_propagate() -> None:
    with pytest.raises(SyntaxProblem):
        format_statechart_text("statechart {", "bad.lr")
