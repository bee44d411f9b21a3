"""Edits of a chart's syntax tree, printed as canonical text that parses back to the edit:
comments stay, imports are added where needed, and edits that do not fit are refused."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.studio import edits
from lightrocks.languages.lightrocks.syntax import parse_statechart

ROOT = Path(__file__).resolve().parents[2]
AHEAD = ROOT / "examples" / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"
PLUG = ROOT / "examples" / "din_rail_ahead" / "tasks" / "PlugTerminalAhead.lr"


def edit(path: Path, change, text: str | None = None) -> str:
    return edits.edited(text or path.read_text(), str(path), change)


def transitions(text: str) -> list[tuple[str, str, str]]:
    chart = parse_statechart(text, "x.lr").statechart
    return [(t.source, t.target, t.stimulus) for t in chart.elements if hasattr(t, "target")]


def test_moving_a_state_along_the_chain_relinks_it_and_moving_back_restores_the_file() -> None:
    moved = edit(AHEAD, edits.at([], edits.move_in_chain("PlugTerminal3", -1)))
    assert transitions(moved)[:4] == [
        ("go", "PlugTerminal1", ""),
        ("PlugTerminal1", "PlugTerminal3", "plugged"),
        ("PlugTerminal3", "PlugTerminal2", "plugged"),
        ("PlugTerminal2", "assembled", "plugged"),
    ]
    assert "// The top-hat rail assembly with look-ahead" in moved
    back = edit(AHEAD, edits.at([], edits.move_in_chain("PlugTerminal3", 1)), moved)
    assert back == AHEAD.read_text()


def test_a_new_state_imports_its_chart_and_a_transition_leads_from_it() -> None:
    def add(unit):
        unit, name = edits.with_import(unit, "din_rail.skills.Retreat")
        return edits.at([], edits.add_state("Away", name))(unit)

    added = edit(AHEAD, add)
    assert "import din_rail.skills.Retreat;\n" in added
    assert '  <<import="Retreat">> state Away;\n' in added
    linked = edit(AHEAD, edits.at([], edits.add_transition("Away", "failed", "retreated")), added)
    assert transitions(linked)[-1] == ("Away", "failed", "retreated")


def test_an_import_that_a_wildcard_covers_is_not_repeated() -> None:
    def add(unit):
        unit, name = edits.with_import(unit, "din_rail.skills.Retreat")
        return edits.at([], edits.add_state("Away", name))(unit)

    added = edit(PLUG, add)
    assert added.count("import ") == PLUG.read_text().count("import ")


def test_deleting_a_state_in_a_region_deletes_its_transitions() -> None:
    deleted = edit(PLUG, edits.at(["PressOn", "Arm"], edits.delete_state("Jammed")))
    assert "final state Jammed;" not in deleted
    assert "Snap -> Jammed jammed;" not in deleted and "Snap -> Latched latched;" in deleted


def test_deleting_an_arrow_deletes_every_transition_it_draws() -> None:
    deleted = edit(PLUG, edits.at([], edits.delete_transitions("BringToRail", "FindTerminal")))
    assert ("BringToRail", "FindTerminal", "lost") not in transitions(deleted)
    assert ("BringToRail", "GiveUp", "lost") in transitions(deleted)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (edits.at([], edits.add_state("PlugTerminal1", "X")), "'PlugTerminal1' is taken"),
        (edits.at([], edits.add_transition("Nowhere", "failed", "")), "no state or condition"),
        (edits.at(["Nothing"], edits.delete_state("A")), "no composite state or region"),
        (edits.at([], edits.move_in_chain("PlugTerminal1", -1)), "already at that end"),
        (edits.at([], edits.delete_transitions("go", "failed")), "no transition from"),
    ],
)
def test_edits_that_do_not_fit_are_refused(change, message: str) -> None:
    with pytest.raises(edits.EditError, match=message):
        edit(AHEAD, change)


def test_a_name_must_be_an_identifier() -> None:
    with pytest.raises(edits.EditError, match="is not a name"):
        edits.add_state("two words", "Retreat")
    with pytest.raises(edits.EditError, match="is not a name"):
        edits.add_transition("A", "B", "a; b")
