"""Completion offers the states of the region at the cursor, not those of other regions."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsprotocol import types as lsp

from lightrocks.app.lsp.completion import completions
from lightrocks.app.lsp.index import FileIndex, Index
from lightrocks.app.lsp.text import Text
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.workbench.incremental import IncrementalCheck

CHART = """\
statechart Plant {
  events { go; stop; }

  initial state Off;
  state On {
    region Pump {
      initial state Idle;
      state Running;
      Idle -> Running go;  // a brace in a comment: }
    }
    region Valve {
      initial state Shut;
      state Open { initial state Half; state Full; Half -> Full go; }
      Shut -> Open go;
    }
  }

  Off -> On go;
  On -> Off stop;
}
"""


@pytest.fixture
def plant(tmp_path: Path) -> tuple[FileIndex, Text]:
    path = tmp_path / "Plant.lr"
    path.write_text(CHART, encoding="utf-8")
    checked = IncrementalCheck([tmp_path])
    assert checked.full() == []
    index = Index()
    index.update(checked.context.workspace, lambda p: Text(p.read_text(encoding="utf-8")))
    return index.files[path.resolve()], Text(CHART)


def states_offered(file: FileIndex, text: Text, line_text: str) -> set[str]:
    """State names completed where ``line_text`` starts."""
    line = next(i for i, line in enumerate(text.lines) if line_text in line)
    items = completions(file, "", lsp.Position(line, text.lines[line].index(line_text)))
    return {i.label for i in items if i.detail in ("state", "pseudostate")}


def test_a_region_offers_its_own_states_and_the_enclosing_ones(plant) -> None:
    file, text = plant
    assert states_offered(file, text, "Idle -> Running go;") == {"Idle", "Running", "Off", "On"}
    assert states_offered(file, text, "Shut -> Open go;") == {"Shut", "Open", "Off", "On"}


def test_a_composite_inside_a_region_adds_its_children(plant) -> None:
    file, text = plant
    offered = states_offered(file, text, "Half -> Full go;")
    assert offered == {"Half", "Full", "Shut", "Open", "Off", "On"}


def test_the_top_level_offers_no_state_of_a_region(plant) -> None:
    file, text = plant
    assert states_offered(file, text, "Off -> On go;") == {"Off", "On"}


def test_states_of_regions_are_declared_in_the_index(plant) -> None:
    file, _ = plant
    declared = {o.name for o in file.occurrences if o.declaration}
    assert {"Idle", "Running", "Shut", "Open", "Half", "Full"} <= declared
    referenced = {o.name for o in file.occurrences if not o.declaration and o.kind == "state"}
    assert {"Idle", "Running", "Shut", "Open", "Half", "Full"} <= referenced


def test_a_region_scope_is_its_span_whatever_braces_its_comments_hold(plant) -> None:
    file, text = plant
    [pump] = [r for r, names in file.scopes if "Idle" in names and "Shut" not in names]
    start = text.lines[pump.start.line].index("region Pump")
    assert (pump.start.character, text.lines[pump.end.line]) == (start, "    }")
    assert pump.end.line == pump.start.line + 4  # past the comment's brace


def test_hover_types_the_innermost_expression_under_the_cursor(tmp_path: Path) -> None:
    source = CHART.replace(
        "  Off -> On go;",
        "  parameters {\n    Length gap = 2 mm;\n    Force push = 3 N;\n  }\n"
        "  Off -> On [(gap + 1 mm) * 2 > 5 mm && push < 4 N] go;",
    )
    path = tmp_path / "Plant.lr"
    path.write_text(source, encoding="utf-8")
    checked = IncrementalCheck([tmp_path])
    assert checked.full() == []
    text = Text(source)
    index = Index()
    inferred = analysis(checked.context).typing.inferred
    index.update(checked.context.workspace, lambda p: Text(p.read_text()), inferred)
    file = index.files[path.resolve()]
    line = next(i for i, row in enumerate(text.lines) if "Off -> On [" in row)

    def hovered(marker: str) -> str:
        column = text.lines[line].index(marker)
        return file.expression_at(lsp.Position(line, column))[1]

    assert hovered("+ 1 mm") == "gap + 1 mm : Length [m]"
    assert hovered("* 2") == "(gap + 1 mm) * 2 : Length [m]"
    assert hovered("> 5") == "(gap + 1 mm) * 2 > 5 mm : Boolean"
    assert hovered("&&").endswith("&& push < 4 N : Boolean")
    assert hovered("< 4") == "push < 4 N : Boolean"
