"""The canonical text of .lrd models: parse -> print -> parse is equal, printing is stable."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.languages.domain.printer import format_domain_text, print_domain
from lightrocks.languages.domain.syntax import parse_domain
from lightrocks.metamodel.grammar import SyntaxProblem

MODELS = sorted((Path(__file__).parent / "models").glob("*.lrd"))


@pytest.mark.parametrize("path", MODELS, ids=lambda p: p.name)
def test_round_trip_and_idempotence(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    printed = print_domain(parse_domain(text, path.name))
    assert parse_domain(printed, path.name) == parse_domain(text, path.name)
    assert print_domain(parse_domain(printed, path.name)) == printed
    assert format_domain_text(printed, path.name) == printed


CELL = """\
package screwing.cell;
device ParallelGripper { command open(); command close(Force force = 20 N);
                         sensor Boolean holding; sensor Length width; }
device Camera { command localize(Object target) returns Frame; }
quantity Length [m]; quantity Angle [rad]; vector J of Angle [7];
cell ScrewingCell { robot : LWR;  gripper : ParallelGripper;  object screw { Length depth = 0 mm; }
  object cube; }
"""

CELL_CANONICAL = """\
package screwing.cell;

device ParallelGripper {
  command open();
  command close(Force force = 20 N);

  sensor Boolean holding;
  sensor Length width;
}

device Camera {
  command localize(Object target) returns Frame;
}

quantity Length [m];
quantity Angle [rad];

vector J of Angle [7];

cell ScrewingCell {
  robot : LWR;
  gripper : ParallelGripper;

  object screw {
    Length depth = 0 mm;
  }

  object cube;
}
"""


def test_canonical_layout() -> None:
    assert format_domain_text(CELL, "cell.lrd") == CELL_CANONICAL


def test_a_bare_number_before_a_range_keeps_its_parentheses() -> None:
    printed = format_domain_text("device D { command c(Real r = 0.5 * 2 in 0 .. 1); }", "d.lrd")
    assert "command c(Real r = (0.5 * 2) in 0 .. 1);" in printed


def test_syntax_errors_propagate() -> None:
    with pytest.raises(SyntaxProblem):
        format_domain_text("device {", "bad.lrd")
