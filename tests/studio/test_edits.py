"""Edits of a chart's syntax tree, printed as canonical text that parses back to the edit:
comments stay, imports are added where needed, and edits that do not fit are refused."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.studio import edits
from lightrocks.languages.lightrocks.syntax import parse_statechart
from studio.charts import composed_part

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


PLAIN = ROOT / "examples" / "din_rail" / "tasks" / "PlugTerminal.lr"


def test_an_action_given_to_a_transition_keeps_the_comment_of_its_line() -> None:
    change = edits.set_transition("BringToRail", "failed", 0, "blocked", "", "terminal.pushes = 1;")
    added = edit(PLAIN, edits.at([], change))
    assert (
        "  BringToRail -> failed blocked / { terminal.pushes = 1; }; "
        "// the terminal stays in the hand for the operator\n" in added
    )
    assert added.count("//") == PLAIN.read_text().count("//")
    back = edit(
        PLAIN,
        edits.at([], edits.set_transition("BringToRail", "failed", 0, "blocked", "", "")),
        added,
    )
    assert back == PLAIN.read_text()


def test_a_new_transition_with_a_block_takes_no_comment_of_the_file_into_it() -> None:
    text = PLAIN.read_text().replace(
        "  Withdraw -> failed retreated;\n", "  Withdraw -> failed retreated;\n  // the end\n"
    )
    change = edits.add_transition(
        "LetGo", "failed", "blocked", "terminal.latched", "a = 1;\nb = 2;"
    )
    added = edit(PLAIN, edits.at([], change), text)
    assert (
        "  Withdraw -> failed retreated;\n"
        "  LetGo -> failed [terminal.latched] blocked / {\n    a = 1;\n    b = 2;\n  };\n"
        "\n  // the end\n\n  property onRail:"
    ) in added


def test_the_composition_forms_write_what_the_shipped_task_says() -> None:
    """A task composed by the forms alone prints as the shipped one, comments aside."""
    shipped = ROOT / "examples" / "din_rail" / "tasks" / "AssembleRail.lr"
    text = edits.new_chart("din_rail.tasks", "AssembleRail", "task", ["din_rail.cell.RailCell"])
    assert text == (
        "package din_rail.tasks;\n\nimport din_rail.cell.RailCell;\n\n"
        "<<task>> statechart AssembleRail { }\n"
    )
    steps = [
        edits.set_parameters([("Length", "across", "0 mm"), ("Length", "clearance", "10mm")]),
        edits.add_condition("start", "go"),
        edits.add_condition("end", "assembled"),
        edits.add_condition("end", "failed"),
    ]
    for number, slot in ((1, "-70 mm"), (2, "0 mm"), (3, "70 mm")):
        steps += [
            edits.add_state(f"PlugTerminal{number}", "PlugTerminal"),
            edits.set_arguments(
                f"PlugTerminal{number}",
                [("terminal", f"terminal{number}"), ("slot", slot), ("grip", " "),
                 ("across", "across"), ("clearance", "clearance")],
            ),
        ]  # fmt: skip
    steps += [
        edits.add_transition("go", "PlugTerminal1", ""),
        edits.add_transition("PlugTerminal1", "PlugTerminal2", "plugged"),
        edits.add_transition("PlugTerminal2", "PlugTerminal3", "plugged"),
        edits.add_transition("PlugTerminal3", "assembled", "plugged"),
    ]
    steps += [edits.add_transition(f"PlugTerminal{n}", "failed", "failed") for n in (1, 2, 3)]
    for step in steps:
        text = edit(shipped, edits.at([], step), text)
    assert composed_part(text) == composed_part(shipped.read_text())


def test_parameters_keep_their_comments_and_a_condition_goes_before_the_states() -> None:
    shipped = ROOT / "examples" / "din_rail" / "tasks" / "AssembleRail.lr"
    rows = [("Length", "across", "0 mm"), ("Length", "clearance", "12 mm"), ("Integer", "n", "")]
    changed = edit(shipped, edits.at([], edits.set_parameters(rows)))
    assert (
        "    Length clearance = 12 mm; // terminal above its latched pose where the careful "
        "descent starts\n"
    ) in changed
    assert "    Length across = 0 mm;     // set-down offset across the rail" in changed
    assert "    Integer n;\n  }" in changed
    removed = edit(shipped, edits.at([], edits.set_parameters([])))
    assert "parameters" not in removed
    assert "\n  // set-down offset across the rail from its localized centre line\n" in removed
    plain = "package p;\n\nstatechart C {\n  state A;\n}\n"
    added = edits.edited(plain, "C.lr", edits.at([], edits.add_condition("end", "done", "true")))
    assert added == "package p;\n\nstatechart C {\n  end condition done [true];\n\n  state A;\n}\n"


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: edits.set_arguments("A", [("slot", "70 +")]), "argument 'slot': syntax error"),
        (lambda: edits.set_arguments("A", [("x", "1"), ("x", "2")]), "given twice"),
        (lambda: edits.add_transition("A", "B", "", "a >", ""), "guard: syntax error"),
        (lambda: edits.add_transition("A", "B", "", "", "a = ;"), "line 1, column 5"),
        (lambda: edits.add_transition("A", "B", "", "", "a = 1"), "action: incomplete"),
        (lambda: edits.set_parameters([("Length m", "a", "")]), "not a type name"),
        (lambda: edits.set_parameters([("Length", "a", ""), ("Real", "a", "")]), "one name"),
        (lambda: edits.add_condition("middle", "x"), "'start' or 'end'"),
        (lambda: edits.new_chart("a b", "C", "task"), "not a package name"),
        (lambda: edits.new_chart("p", "C", "robot"), "none of task"),
    ],
)
def test_form_texts_are_read_by_the_language_s_parser(make, message: str) -> None:
    with pytest.raises(edits.EditError, match=message):
        make()
